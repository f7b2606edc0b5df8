"""Reading a `gasp-pairs --pairs-csv` file for the summary scripts (standard library only)."""
import csv
import sys


def read_pairs_csv(path, method, needed, what):
    """The rows of `method` in the pairs CSV at `path`; exits with a message naming the file when
    it cannot be read or lacks a column of `needed` (`what` says which columns, for the message)."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            missing = sorted(set(needed) - set(reader.fieldnames or []))
            if missing:
                sys.exit("error: %s: not a gasp-pairs --pairs-csv file with the %s (missing: %s)"
                         % (path, what, ", ".join(missing)))
            return [r for r in reader if r["method"] == method]
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))


def pop_option(args, name, default, what):
    """Removes `name VALUE` from the argument list `args` and returns VALUE (`default` without
    the option); exits with "error: NAME needs WHAT" when the value is missing."""
    if name not in args:
        return default
    k = args.index(name)
    if k + 1 >= len(args):
        sys.exit("error: %s needs %s" % (name, what))
    value = args[k + 1]
    del args[k:k + 2]
    return value
