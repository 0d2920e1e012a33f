"""Expressions of a particle's position, the initial fields of a body (`velocity = ["0.8 * y",
"0"]`): parsed with Python's `ast` module and evaluated by walking the tree into NumPy
operations over the coordinate arrays. Nothing is ever handed to `eval` or `exec`: only the
grammar below is accepted, every other construct is refused by name.

Grammar (Python's own syntax and precedence, restricted)::

    expr    := number | name | expr op expr | -expr | +expr | (expr) | call
    op      := + | - | * | / | **                (** binds tighter than unary minus: -x**2
                                                  is -(x**2), as in Python)
    name    := x | y | z                          (y from 2D, z in 3D: the particle position)
             | pi | e
    call    := f(expr)        f in sin cos tan arcsin arccos arctan sinh cosh tanh
                                   exp log log10 sqrt abs
             | atan2(y, x) | min(a, b, ...) | max(a, b, ...)    (elementwise)
             | where(cond, a, b)                  (a where cond holds, else b)
    cond    := expr cmp expr [cmp expr ...]       (cmp: < <= > >= == !=; chains as Python's)
             | cond and cond | cond or cond | not cond | (cond)

Conditions appear only as the first argument of `where`. Numbers are taken as float64, so
`10**400` is inf (refused as not finite where the field is evaluated), never a huge integer.
"""
import ast
import math
from dataclasses import dataclass, field

import numpy as np


#: the functions of one argument, by name (NumPy's elementwise ufuncs)
UNARY = {
    "sin": np.sin, "cos": np.cos, "tan": np.tan,
    "arcsin": np.arcsin, "arccos": np.arccos, "arctan": np.arctan,
    "sinh": np.sinh, "cosh": np.cosh, "tanh": np.tanh,
    "exp": np.exp, "log": np.log, "log10": np.log10, "sqrt": np.sqrt, "abs": np.abs,
}
#: the other functions: name -> (ufunc, least arguments, most arguments or None)
OTHER = {"atan2": (np.arctan2, 2, 2), "min": (np.minimum, 2, None),
         "max": (np.maximum, 2, None), "where": (np.where, 3, 3)}
FUNCTIONS = tuple(UNARY) + tuple(OTHER)
CONSTANTS = {"pi": math.pi, "e": math.e}
AXES = ("x", "y", "z")

_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
           ast.Div: np.true_divide, ast.Pow: np.power}
_COMPARE = {ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater,
            ast.GtE: np.greater_equal, ast.Eq: np.equal, ast.NotEq: np.not_equal}
#: what a refused construct is called in the message (the rest by their ast class name)
_NAMES = {ast.Attribute: "attribute access ('.')", ast.Subscript: "indexing ('[]')",
          ast.Lambda: "lambda", ast.IfExp: "'a if c else b' (use where(c, a, b))",
          ast.Mod: "'%'", ast.FloorDiv: "'//'", ast.MatMult: "'@'", ast.BitAnd: "'&'",
          ast.BitOr: "'|'", ast.BitXor: "'^' (use ** for a power)", ast.LShift: "'<<'",
          ast.RShift: "'>>'", ast.Invert: "'~'", ast.Tuple: "a tuple (',')",
          ast.List: "a list", ast.Starred: "'*' unpacking", ast.NamedExpr: "':='",
          ast.JoinedStr: "an f-string", ast.Dict: "a dict", ast.Set: "a set",
          ast.Is: "'is'", ast.IsNot: "'is not'", ast.In: "'in'", ast.NotIn: "'not in'"}
#: longest expression text, and most tree nodes: a field is a formula, not a program (and
#: the bound keeps the recursive walks far from Python's recursion limit)
MAX_CHARS = 2000
MAX_NODES = 400
MAX_DEPTH = 60


def allowed_names(dim):
    """The names an expression of a `dim`-dimensional scene may use."""
    return AXES[:dim] + tuple(CONSTANTS)


def _refuse(node):
    what = _NAMES.get(type(node), type(node).__name__)
    raise ValueError(f"{what} is not allowed in an expression")


class _Checker:
    """Validates a parsed tree against the grammar (raises ValueError with the reason)."""

    def __init__(self, dim):
        self.dim = dim
        self.nodes = 0

    def value(self, node, depth=0):
        self._count(depth)
        if isinstance(node, ast.Constant):
            v = node.value
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise ValueError(f"{v!r} is not a number (only numbers, names and "
                                 "functions are allowed)")
            try:
                finite = math.isfinite(float(v))
            except OverflowError:
                finite = False
            if not finite:
                raise ValueError(f"the number {str(v)[:20]} is too large for a float")
        elif isinstance(node, ast.Name):
            names = allowed_names(self.dim)
            if node.id not in names:
                if node.id in FUNCTIONS:
                    raise ValueError(f"{node.id!r} is a function: call it, {node.id}(...)")
                raise ValueError(f"unknown name {node.id!r}; allowed: {', '.join(names)}")
        elif isinstance(node, ast.BinOp):
            if type(node.op) not in _BINARY:
                _refuse(node.op)
            self.value(node.left, depth + 1)
            self.value(node.right, depth + 1)
        elif isinstance(node, ast.UnaryOp):
            if not isinstance(node.op, (ast.USub, ast.UAdd)):
                if isinstance(node.op, ast.Not):
                    raise ValueError("'not' belongs in the condition of where(cond, a, b)")
                _refuse(node.op)
            self.value(node.operand, depth + 1)
        elif isinstance(node, ast.Call):
            self._call(node, depth)
        elif isinstance(node, (ast.Compare, ast.BoolOp)):
            raise ValueError("a comparison is a condition: it belongs in the first argument "
                             "of where(cond, a, b)")
        else:
            _refuse(node)

    def condition(self, node, depth):
        self._count(depth)
        if isinstance(node, ast.Compare):
            for op in node.ops:
                if type(op) not in _COMPARE:
                    _refuse(op)
            for side in (node.left, *node.comparators):
                self.value(side, depth + 1)
        elif isinstance(node, ast.BoolOp):
            for v in node.values:
                self.condition(v, depth + 1)
        elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            self.condition(node.operand, depth + 1)
        else:
            raise ValueError("the first argument of where must be a comparison, e.g. "
                             "where(x < 0.5, 1, 0)")

    def _call(self, node, depth):
        f = node.func
        if not isinstance(f, ast.Name):
            raise ValueError("only the listed functions may be called, by name")
        if f.id not in FUNCTIONS:
            raise ValueError(f"function {f.id!r} is not allowed; functions: "
                             f"{', '.join(FUNCTIONS)}")
        if node.keywords:
            raise ValueError(f"{f.id}() takes no keyword arguments")
        if any(isinstance(a, ast.Starred) for a in node.args):
            _refuse(ast.Starred())
        lo, hi = (1, 1) if f.id in UNARY else OTHER[f.id][1:]
        n = len(node.args)
        if n < lo or (hi is not None and n > hi):
            want = str(lo) if lo == hi else f"{lo} or more"
            raise ValueError(f"{f.id}() takes {want} argument{'s' * (want != '1')}, got {n}")
        for i, a in enumerate(node.args):
            if f.id == "where" and i == 0:
                self.condition(a, depth + 1)
            else:
                self.value(a, depth + 1)

    def _count(self, depth):
        self.nodes += 1
        if self.nodes > MAX_NODES or depth > MAX_DEPTH:
            raise ValueError(f"too long: at most {MAX_NODES} terms nested {MAX_DEPTH} deep")


def _syntax_reason(exc, text):
    """`syntax error at column 5 near ')': <Python's message>`."""
    col = exc.offset or 0
    if 0 < col <= len(text):
        near = text[col - 1: col + 9].strip()
        where = f"at column {col}" + (f" near {near!r}" if near else "")
    else:  # (Python puts an unfinished expression at 0 or past its end)
        where = "at the end"
    return f"syntax error {where}: {exc.msg}"


@dataclass(frozen=True)
class Expression:
    """One checked expression of the position; `evaluate(x)` over an (n, dim) array."""
    text: str
    dim: int
    tree: ast.AST = field(repr=False, compare=False)

    def evaluate(self, x):
        """The values at the points x (n, dim) as a float64 array (n,). Not checked for
        finiteness here (see `initial_fields`)."""
        with np.errstate(all="ignore"):  # log(0), x / 0: decided by the caller, not warned
            v = _Eval(x).value(self.tree)
        return np.broadcast_to(np.asarray(v, np.float64), (len(x),)).copy()

    def __str__(self):
        return self.text


def parse(text, dim):
    """An `Expression` of the position in `dim` dimensions; ValueError with the reason (no
    key: the caller names it) when `text` is not of the grammar."""
    if not isinstance(text, str):
        raise ValueError(f"expected a number or an expression string, got {type(text).__name__}")
    if len(text) > MAX_CHARS:
        raise ValueError(f"{len(text)} characters: an expression may have {MAX_CHARS}")
    if not text.strip():
        raise ValueError("empty expression")
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except SyntaxError as exc:
        raise ValueError(_syntax_reason(exc, text.strip())) from None
    except (RecursionError, MemoryError):  # the parser nests as deep as the parentheses
        raise ValueError("nested too deep") from None
    except ValueError as exc:  # (a NUL character, on some Python versions)
        raise ValueError(f"syntax error: {exc}") from None
    _Checker(dim).value(tree)
    return Expression(text, dim, tree)


class _Eval:
    """Walks a checked tree: each node a NumPy array over the points (or a float)."""

    def __init__(self, x):
        self.x = x

    def value(self, node):
        if isinstance(node, ast.Constant):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id in CONSTANTS:
                return CONSTANTS[node.id]
            return self.x[:, AXES.index(node.id)].astype(np.float64)
        if isinstance(node, ast.BinOp):
            return _BINARY[type(node.op)](np.float64(self.value(node.left)),
                                          np.float64(self.value(node.right)))
        if isinstance(node, ast.UnaryOp):
            v = np.float64(self.value(node.operand))
            return -v if isinstance(node.op, ast.USub) else v
        name = node.func.id  # a call (the checker let nothing else through)
        if name == "where":
            cond, a, b = node.args
            return np.where(self.condition(cond), self.value(a), self.value(b))
        args = [np.float64(self.value(a)) for a in node.args]
        if name in UNARY:
            return UNARY[name](args[0])
        ufunc = OTHER[name][0]
        out = args[0]
        for a in args[1:]:  # min / max of several: pairwise, left to right
            out = ufunc(out, a)
        return out

    def condition(self, node):
        if isinstance(node, ast.Compare):
            left = self.value(node.left)
            out = True
            for op, right in zip(node.ops, node.comparators):  # a < b < c: a < b and b < c
                right = self.value(right)
                out = np.logical_and(out, _COMPARE[type(op)](left, right))
                left = right
            return out
        if isinstance(node, ast.BoolOp):
            join = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            out = self.condition(node.values[0])
            for v in node.values[1:]:
                out = join(out, self.condition(v))
            return out
        return np.logical_not(self.condition(node.operand))  # `not`

