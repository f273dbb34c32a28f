"""The one exception of the link: what went wrong, said so that the user knows what to do."""

from __future__ import annotations


class LinkError(Exception):
    """A failure of the link (no pyserial, a port that cannot be opened, a lost reply, ...).

    `device_state` says what is known about the device when the failure happened, so that the
    user is never left guessing what is on it.
    """

    def __init__(self, message: str, device_state: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.device_state = device_state
