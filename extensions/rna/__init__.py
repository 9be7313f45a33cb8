"""ROS knowledge for rna-template: naming rules, interface types, parameters, licenses.

Everything here is plain Python without Copier, so it is unit-tested on its own;
`extensions/copier_glue.py` exposes it to the templates.
"""

from . import code, configs, integrate, names, workspace
from .model import AnswerError, Package, build_package, question_error, split_list

__all__ = ["AnswerError", "Package", "build_package", "code", "configs", "integrate", "names", "question_error",
           "split_list", "workspace"]
