"""The numbered migrations, oldest first: add one at the end, never edit a shipped one."""
