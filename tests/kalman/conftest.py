"""The copy of filterpy's test file is run by test_filterpy_suite.py with renames, not alone."""

collect_ignore = ["filterpy_test_ukf.py"]
