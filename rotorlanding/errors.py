"""One exception type for bad user input.

Every problem with a user's file or option is raised as :class:`InputError`, which names the
file, the field (dotted path as written in the TOML), the offending value and what is allowed.
The CLI prints ``str(err)`` on one line and exits with code 2; library users can catch it.
"""

from __future__ import annotations


class InputError(ValueError):
    """Bad user input: file, field, value and what is allowed."""

    def __init__(self, field: str, value, allowed: str, file: str | None = None):
        self.field = field
        self.value = value
        self.allowed = allowed
        self.file = file
        super().__init__(self._text())

    def _text(self) -> str:
        where = f"{self.file}: " if self.file else ""
        return f"{where}{self.field} = {self.value!r}: {self.allowed}"

    def with_file(self, file: str) -> "InputError":
        """Return the same error attributed to ``file`` (if it has none yet)."""
        if self.file is None:
            self.file = str(file)
            self.args = (self._text(),)
        return self

    def __str__(self) -> str:  # keep it one line whatever the value holds
        return self._text().replace("\n", " ")
