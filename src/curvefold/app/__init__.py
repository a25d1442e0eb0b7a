"""The application layer: design files, the command line and the output folder."""
