"""Pictures: views of structures and vaults, plots and the HTML report."""
