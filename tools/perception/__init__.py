"""Offline tools for the obstacle classifier: render the dataset, train, evaluate (not used at run time)."""
