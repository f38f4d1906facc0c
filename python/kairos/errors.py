# SPDX-License-Identifier: MIT
"""Exceptions: one class per failure status of the C API, all under :class:`Error`.

A failed call raises the class of its status with the library's message (``kairos_last_error``),
which names the argument and the bad value, e.g. ``poses_a[5].orientation must be a unit
quaternion``. On failure the library writes nothing and changes nothing, so the Python objects
are as they were before the call.

Arguments the package refuses before reaching the library (an array of the wrong shape, an
integer that does not fit the C field) raise plain ``ValueError`` or ``TypeError``.
"""

from __future__ import annotations

from typing import Dict, NoReturn, Type

from . import _capi

__all__ = [
    "Error", "NullArgumentError", "InvalidArgumentError", "StructSizeError", "DegenerateError",
    "StaleIdError", "OutOfMemoryError", "UnimplementedError", "UnsupportedVersionError",
    "InternalError", "LimitError", "status_name", "last_error",
]


class Error(Exception):
    """A call into libkairos failed.

    Attributes:
        status: the C status (a negative ``KAIROS_ERROR_*`` value).
        status_name: its name, e.g. ``"KAIROS_ERROR_INVALID_ARGUMENT"``.
        message: the library's message (also ``str(error)``).
    """

    status: int
    status_name: str
    message: str

    def __init__(self, message: str, status: int = _capi.ERROR_INTERNAL,
                 status_name: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.status = status
        self.status_name = status_name or status_name_of(status)

    def __str__(self) -> str:
        return self.message

    def __reduce__(self):  # picklable across processes (multiprocessing pools)
        return (type(self), (self.message, self.status, self.status_name))


class NullArgumentError(Error):
    """KAIROS_ERROR_NULL_ARGUMENT: a required pointer was NULL (e.g. a closed shape)."""


class InvalidArgumentError(Error, ValueError):
    """KAIROS_ERROR_INVALID_ARGUMENT: a NaN or infinite number, a size <= 0, a quaternion not of
    unit length within KAIROS_QUAT_TOLERANCE, a singular matrix, an unknown enum value, a
    magnitude beyond KAIROS_MAX_MAGNITUDE, a static object moved."""


class StructSizeError(Error):
    """KAIROS_ERROR_STRUCT_SIZE: a settings struct of the wrong size (a bug in this package)."""


class DegenerateError(Error, ValueError):
    """KAIROS_ERROR_DEGENERATE: input that names no shape (no points, a collinear triangle)."""


class StaleIdError(Error, LookupError):
    """KAIROS_ERROR_STALE_ID: an object id that is 0, unknown, or of a removed object."""


class OutOfMemoryError(Error, MemoryError):
    """KAIROS_ERROR_OUT_OF_MEMORY: an allocation failed; nothing was changed."""


class UnimplementedError(Error, NotImplementedError):
    """KAIROS_ERROR_NOT_IMPLEMENTED: declared in the contract, not built in this library."""


class UnsupportedVersionError(Error):
    """KAIROS_ERROR_UNSUPPORTED_VERSION: an ABI version the library does not provide."""


class InternalError(Error):
    """KAIROS_ERROR_INTERNAL: a bug in Kairos; please report it with the message."""


class LimitError(Error):
    """KAIROS_ERROR_LIMIT: a count beyond what the library supports (more than 2**32 - 1
    objects)."""


_BY_STATUS: Dict[int, Type[Error]] = {
    _capi.ERROR_NULL_ARGUMENT: NullArgumentError,
    _capi.ERROR_INVALID_ARGUMENT: InvalidArgumentError,
    _capi.ERROR_STRUCT_SIZE: StructSizeError,
    _capi.ERROR_DEGENERATE: DegenerateError,
    _capi.ERROR_STALE_ID: StaleIdError,
    _capi.ERROR_OUT_OF_MEMORY: OutOfMemoryError,
    _capi.ERROR_NOT_IMPLEMENTED: UnimplementedError,
    _capi.ERROR_UNSUPPORTED_VERSION: UnsupportedVersionError,
    _capi.ERROR_INTERNAL: InternalError,
    _capi.ERROR_LIMIT: LimitError,
}

_lib = _capi.lib


def status_name_of(status: int) -> str:
    return _lib.kairos_status_name(status).decode("ascii", "replace")


def status_name(status: int) -> str:
    """The C name of a status value, e.g. ``"KAIROS_ERROR_NULL_ARGUMENT"``
    (``"KAIROS_UNKNOWN_STATUS"`` for values this library does not know)."""
    return status_name_of(int(status))


def last_error() -> str:
    """The message of the last failed call on this thread ("" when none has failed)."""
    return _lib.kairos_last_error().decode("utf-8", "replace")


def error_for(status: int) -> Error:
    """The exception for a failure status, carrying this thread's last error message.

    Must be called on the thread that made the failing call, before any other call fails there
    (the message buffer is per thread)."""
    cls = _BY_STATUS.get(status, Error)
    return cls(last_error(), status, status_name_of(status))


def raise_status(status: int) -> NoReturn:
    raise error_for(status)


def check(status: int) -> None:
    """Raises the exception of a failure status; returns for KAIROS_OK."""
    if status:
        raise error_for(status)
