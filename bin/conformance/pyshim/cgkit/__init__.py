"""Stand-in for the parts of cgkit 2 that the Aqsis regression helpers use (see ../README.md)."""
