"""How the workbench's scripts (compare/figures.py, compare/pbd_figures.py, scripts/render_frames.py)
report a write that failed: one line "<file>: write failed (<reason>)" and exit status 74
(WRITE_FAILED, sysexits' EX_IOERR; workbench::kWriteFailedStatus in workbench/child_process.h).

The line goes back to the workbench on the script's standard input, a socket from the workbench
(workbench::ChildProcess), because the log the script's stderr goes to may be on the very disk
that is full; it is also printed to stderr for a person running the script by hand.
"""
import errno
import os
import stat
import sys

WRITE_FAILED = 74

# The reasons a write fails for lack of room or a broken disk: ffmpeg reports them by strerror.
DISK_ERRORS = (errno.ENOSPC, errno.EFBIG, errno.EIO, errno.EDQUOT)


def write_failed(path, err):
    """Reports OSError `err` from writing `path` and ends this process (and only it) at once."""
    message = f"{path}: write failed ({err.strerror or err})\n"
    try:
        if stat.S_ISSOCK(os.fstat(0).st_mode):
            os.write(0, message.encode())
    except OSError:
        pass
    try:
        os.write(2, message.encode())
    except OSError:
        pass
    os._exit(WRITE_FAILED)  # no exit handlers: flushing the log could fail again


def tell_workbench(line):
    """Writes `line` back to the workbench on standard input, the socket it runs this script with
    (workbench::ChildProcess::receive)."""
    os.write(0, (line + "\n").encode())


def disk_error_text(text):
    """The strerror text of a disk error found in a tool's message (ffmpeg's), else None."""
    for code in DISK_ERRORS:
        if os.strerror(code) in text:
            return os.strerror(code)
    return None


def guarded(main):
    """Runs main(); an OSError from a write it did not catch itself (its log, a figure) is reported as
    a failed write of the file it names (the log when it names none)."""
    try:
        main()
    except OSError as err:
        if err.errno not in DISK_ERRORS:
            raise
        path = err.filename
        if path is None:
            try:
                path = os.readlink("/proc/self/fd/2")
            except OSError:
                path = "the script's log"
        write_failed(path, err)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except OSError as err:
        write_failed(os.readlink("/proc/self/fd/1"), err)
