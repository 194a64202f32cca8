"""What evo requires of a TUM trajectory file, checked here because evo itself cannot be installed on the
test machines. Written from evo's reader (evo/tools/file_interface.py, read_tum_trajectory_file) and its
trajectory check (evo/core/trajectory.py, PoseTrajectory3D.check):

- a line that starts with '#' is a comment; every other line is a pose, blank lines included;
- a pose is `t x y z qx qy qz qw`: fields split on each single space (csv, delimiter ' '), so exactly eight,
  with no tab, no double space and no trailing space;
- every field is a number (we also demand a finite one: evo's poses must be valid SE(3));
- the quaternion has unit norm (numpy.allclose to 1);
- the timestamps are strictly ascending (sorted and unique); evo_ape aborts otherwise;
- there is at least one pose (evo cannot index an empty matrix).
"""
import math


def tum_violations(text, name="trajectory"):
    """Every rule `text` breaks, one message each with its line number; an empty list for a valid file."""
    problems = []
    previous_time = None
    poses = 0
    lines = text.split("\n")
    if lines[-1] == "":
        lines.pop()  # the final newline ends the last line; it does not start an empty one
    for number, line in enumerate(lines, start=1):
        if line.startswith("#"):
            continue
        where = f"{name}:{number}"
        fields = line.split(" ")
        if len(fields) != 8:
            problems.append(f"{where}: {len(fields)} space-separated fields, not 8: {line!r}")
            continue
        try:
            values = [float(f) for f in fields]
        except ValueError:
            problems.append(f"{where}: a field is not a number: {line!r}")
            continue
        if not all(math.isfinite(v) for v in values):
            problems.append(f"{where}: a field is not finite: {line!r}")
            continue
        poses += 1
        t, norm = values[0], math.sqrt(sum(v * v for v in values[4:]))
        if abs(norm - 1.0) > 1e-8 + 1e-5:  # numpy.allclose's default tolerances
            problems.append(f"{where}: the quaternion's norm is {norm}, not 1")
        if previous_time is not None and not t > previous_time:
            problems.append(f"{where}: time {t!r} does not follow {previous_time!r} (evo: not ascending)")
        previous_time = t
    if poses == 0:
        problems.append(f"{name}: no pose")
    return problems
