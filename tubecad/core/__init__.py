"""What every stage shares and nothing above it: errors (each naming its spec key), units,
input validation, the one fit-tolerance policy, atomic file writes, progress callbacks and
lazy package exports. It imports no other tubecad package."""
