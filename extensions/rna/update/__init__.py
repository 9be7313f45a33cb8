"""What runs around `copier update` so that it never loses what the user wrote.

Copier's update renders the old template version with the recorded answers, diffs that
against the project, renders the new version with the new answers and re-applies the
diff. It cannot know which files are the user's, deletes a file its answers no longer
make whether or not it was edited, and merges config files and managed blocks line by
line. The modules here finish its work, one job each:

- `project`: the update's three views of every file: as committed (the user's), as the
  old version rendered it, as the new version renders it; and the project after Copier.
- `resolve`: the answers as stored (each node's language written out) and their checksum.
- `refusals`: answer changes refused before anything is written (ROS generation, a
  node's language changing by itself, a new node landing on the user's own files, ROS 2
  back to ROS 1, a node ported while the package around it is still catkin's).
- `renames`: a node or the package renamed carries the user's files, values and lines.
- `protect`: an edited file the answers no longer make is kept; untouched starters refreshed.
- `config_merge`: config files merged by parameter in the user's own text.
- `blocks`: managed blocks that leave out what the user declares, and dependencies the
  user's code still uses.
- `drift`: user files whose starter changed in a way their code depends on.
- `port`: a ROS 1 package ported to ROS 2: the user's files carried by the rules of rna.port.
- `summary`: what the update did, and what the user must do.
"""
