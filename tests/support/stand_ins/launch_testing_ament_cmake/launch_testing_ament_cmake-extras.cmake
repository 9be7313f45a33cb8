# launch_testing has no wheel: a generated launch test is checked statically instead
# (docs/pages/reference/testing.md).
function(add_launch_test file)
  message(STATUS "stand-in: ${file} is not registered (launch_testing has no wheel)")
endfunction()
