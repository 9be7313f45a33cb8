"""ROS 1 -> ROS 2: what an update to a ROS 2 distribution does with a catkin package's code.

`copier update --trust -d ros_distro=<ROS 2 distro>` regenerates every file the template
owns for ROS 2 (base classes, build files, launch file, config files, tests, interfaces).
The modules here port what the user wrote, as pure functions of text, each rewrite named
by a rule of one table:

- `rules`: the one table of rewrites, and of the ROS 1 calls no rule rewrites (their lines
  are left as they were, marked `TODO(port)` with the ROS 2 equivalent); the docs show it;
- `api`: the base-class API a node's code calls, ROS 1 -> ROS 2 (callbacks, members,
  parameters), one table per language;
- `python`, `cpp`: the rewriters of a node's code and of the user's other code files;
- `dependencies`: ROS 1 packages -> their ROS 2 counterparts;
- `build`: the user's lines of CMakeLists.txt, package.xml and the launch file carried
  over with port notes, and config files in `ros__parameters` form;
- `code`: a node file ported: the rules on the user's text and on the old starter, then a
  three-way merge with the new starter.

rna.update.port runs them on a project.
"""

from .rule import Rule
from .rules import RULES

__all__ = ["RULES", "Rule"]
