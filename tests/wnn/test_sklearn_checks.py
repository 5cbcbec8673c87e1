"""The default ``WNNRegressor()`` passes every check of scikit-learn's ``check_estimator``.

The checks run the default estimator (``n_hidden=20``, 50 EKF epochs), as a user gets it:
nothing is shrunk to make them pass. ``random_state`` is set by the checks themselves
(``set_random_state``), which is why the seed is called that.
"""

from sklearn.utils.estimator_checks import parametrize_with_checks

from filterwnn.wnn.regressor import WNNRegressor


@parametrize_with_checks([WNNRegressor()])
def test_scikit_learn_check(estimator, check):
    check(estimator)
