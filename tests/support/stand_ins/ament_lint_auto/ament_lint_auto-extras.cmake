# The linters ament_lint_common would register are run by the ROS 2 tier itself
# (tests/support/ros2.py: ament_flake8, ament_pep257, ament_cpplint, ament_uncrustify).
macro(ament_lint_auto_find_test_dependencies)
endmacro()
