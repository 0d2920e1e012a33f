"""Case files and the Python scene API -> frozen, validated `Case` (no MPI, no numba)."""
from .case import Case
from .load import case_from_dict, load_case_file, load_case_text, parse_set

__all__ = ["Case", "case_from_dict", "load_case_file", "load_case_text", "parse_set"]
