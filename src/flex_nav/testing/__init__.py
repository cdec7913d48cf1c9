"""The test harness, shipped so users can test their own nodes and states the same way: a private master on a
free port, bounded process management, network namespaces for two-host tests. Nothing below imports it."""
