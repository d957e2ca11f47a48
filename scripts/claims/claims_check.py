"""A claims row's criterion as data, so that the verdict is computed in one place
and a test can show that every row can fail: `check` is an interval for the
measured value, each end optional and open or closed. A row whose interval has
no finite end would accept anything; check_claims_can_fail.py refuses such rows
and pushes each row's measured value past an end to see "no"."""
import math


def check(low=None, high=None, low_open=False, high_open=False):
    """The accepted interval: low <= x <= high (< with *_open); None: unbounded."""
    if low is None and high is None:
        raise ValueError("a criterion needs at least one finite bound")
    return {"low": low, "high": high, "low_open": low_open, "high_open": high_open}


def judge(measured, c):
    """True when measured lies in the interval (a missing or non-finite value never does)."""
    if not isinstance(measured, (int, float)) or isinstance(measured, bool) or not math.isfinite(measured):
        return False
    if c["low"] is not None and (measured <= c["low"] if c["low_open"] else measured < c["low"]):
        return False
    if c["high"] is not None and (measured >= c["high"] if c["high_open"] else measured > c["high"]):
        return False
    return True


def outside(c):
    """A value the interval rejects: past its upper end if it has one, else below its lower."""
    if c["high"] is not None:
        return c["high"] + max(1.0, abs(c["high"]))
    return c["low"] - max(1.0, abs(c["low"]))


def within_factor(low, high, factor):
    """The seed's interval [low, high] widened by `factor` both ways."""
    return check(low / factor, high * factor)
