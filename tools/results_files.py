"""How Rumble's Python scripts write into a results directory, as the engine does
(engine/results/include/results/new_file.hpp): every file is a new file; whatever stands at its name (an old
plot, a symbolic link planted there) is removed first and never followed."""
import os


def open_new(path, mode="wb"):
    """Opens `path` as a new file for writing (binary by default)."""
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666)
    return os.fdopen(fd, mode)
