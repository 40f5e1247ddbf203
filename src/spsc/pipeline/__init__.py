"""The spsc command line and the study runner."""
