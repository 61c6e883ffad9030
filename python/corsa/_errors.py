"""corsa.InputError raised from Python code, with the same text and attributes as from C++."""

from ._corsa import InputError


def input_error(file, message, line=None):
    """An InputError for `file` (and `line`), worded as the command line words errors."""
    file = str(file)
    text = f"{file}:{line}: error: {message}" if line else f"{file}: error: {message}"
    error = InputError(text)
    error.file = file
    error.line = line
    error.record = None
    error.path = ""
    error.message = message
    error.diagnostics = [{"severity": "error", "file": file, "line": line, "record": None,
                          "path": "", "message": message, "text": text}]
    return error
