"""ROS knowledge for rna-template, along the pipeline answers -> model -> code.

- `answers`: Copier's answers, each read once and checked; `build_package()` makes the model.
- `model`: the package, its nodes and endpoints in ROS terms, their files (`layout`) and the
  packages they need (`features`).
- `dialects`: how ROS 2 C++, ROS 2 Python, ROS 1 C++ and ROS 1 Python spell the code.
- Rules and facts the stages share: `names`, `ros`, `interfaces`, `definitions`, `parameters`,
  `licenses`, `wording`; and the files around a package: `configs`, `integrate`, `workspace`.
- `update`: what runs around `copier update`; `port`: the rules that port a ROS 1
  package's code to ROS 2 (rna.update.port runs them).

Everything here is plain Python without Copier, so it is unit-tested on its own;
`extensions/copier_glue.py` exposes it to the templates.
"""

from .answers import AnswerError, Answers, build_package, question_error
from .model import Package

__all__ = ["AnswerError", "Answers", "Package", "build_package", "question_error"]
