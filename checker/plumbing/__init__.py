"""Process plumbing with no engine in it: forked calls, signals, interpreter and dependency tuning,
data folders."""
