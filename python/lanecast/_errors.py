"""lanecast's exceptions (the Rust extension raises them too)."""


class SceneError(ValueError):
    """Bad content in a scene or mesh file, where the command line would report it.

    ``str(e)`` is the command line's message (``FILE:LINE:COL: message``); ``file`` is the
    file, ``line`` its 1-based line and ``column`` its 1-based column (0: the whole line).
    ``line`` and ``column`` are None when the message is about the file as a whole (no camera
    line, not UTF-8, a face of a mesh rendered alone).
    """

    def __init__(self, message, file=None, line=None, column=None):
        super().__init__(message)
        self.file = file
        self.line = line
        self.column = column

    def __reduce__(self):
        return (type(self), (str(self), self.file, self.line, self.column))
