"""vbi's extreme-value fits side by side with scipy's maximum-likelihood fits (issue 48: "vbi's
Gumbel/GEV fit of the same block maxima agrees with scipy's maximum-likelihood fit"), on the
block maxima `vbi.lifetime` computes and on samples of known laws; and the fits of
`vbi.lifetime`'s attrs against `vbi lifetime`'s lifetime.json and `vbi.fit_block_maxima`.

Both programs maximise the same likelihood (Coles 2001, eq. 3.7); they differ only in the
optimiser and its stopping rule. scipy's `genextreme.fit` minimises with `optimize.fmin`
(Nelder–Mead) at a tolerance of 1e-4 by default, and its default start can stall far from the
maximum (on the hourly moments below it stops at ξ = 8.6, 177 log-likelihood units short), so
it is run here from the Gumbel fit (its own `gumbel_r.fit`, ξ = 0) with `fmin` at 1e-10.
Then the two maxima agree in log-likelihood to 1e-9 relative and in parameters to 1e-5 (the
flat direction of the likelihood near its maximum lets parameters differ by about the square
root of the likelihood's tolerance). scipy's `genextreme` has c = −ξ."""

from __future__ import annotations

import numpy as np
import pytest

import vbi
from conftest import EXAMPLES, read_json, run_command

scipy_stats = pytest.importorskip("scipy.stats")
scipy_optimize = pytest.importorskip("scipy.optimize")

HOURLY = EXAMPLES / "lifetime" / "auxerre-3-days-hourly-1x30.toml"


def tight(function, start, args=(), disp=0):
    return scipy_optimize.fmin(
        function, start, args, xtol=1e-10, ftol=1e-13, maxiter=20_000, maxfun=20_000, disp=0
    )


def scipy_gev(values):
    """scipy's GEV maximum-likelihood fit as (location, scale, ξ, log-likelihood)."""
    location, scale = scipy_stats.gumbel_r.fit(values)
    c, location, scale = scipy_stats.genextreme.fit(
        values, 0.0, loc=location, scale=scale, optimizer=tight
    )
    return location, scale, -c, scipy_stats.genextreme.logpdf(values, c, location, scale).sum()


def assert_same_gev(fit, values):
    location, scale, shape, log_likelihood = scipy_gev(values)
    assert fit["log_likelihood"] >= log_likelihood - 1e-9 * abs(log_likelihood)
    assert fit["log_likelihood"] == pytest.approx(log_likelihood, rel=1e-9, abs=1e-9)
    assert fit["location"] == pytest.approx(location, abs=1e-5 * scale)
    assert fit["scale"] == pytest.approx(scale, rel=1e-5)
    assert fit["shape"] == pytest.approx(shape, abs=1e-5)


def assert_same_gumbel(fit, values):
    # scipy solves the Gumbel likelihood equations directly (gumbel_r.fit): to round-off.
    location, scale = scipy_stats.gumbel_r.fit(values)
    assert fit["location"] == pytest.approx(location, abs=1e-10 * scale)
    assert fit["scale"] == pytest.approx(scale, rel=1e-10)
    assert fit["shape"] == 0.0


@pytest.fixture(scope="module")
def hourly():
    return vbi.lifetime(HOURLY)


@pytest.mark.parametrize("seed, shape", [(1, -0.3), (2, -0.1), (3, 0.0), (4, 0.2)])
def test_gev_and_gumbel_fits_of_known_laws_agree_with_scipy(seed, shape):
    values = scipy_stats.genextreme.rvs(
        -shape, loc=5.0e5, scale=6.0e4, size=250, random_state=np.random.default_rng(seed)
    )
    assert_same_gev(vbi.fit_extreme_value(values, "gev"), values)
    assert_same_gumbel(vbi.fit_extreme_value(values, "gumbel"), values)


def test_the_fits_of_vbi_lifetime_s_block_maxima_agree_with_scipy(hourly):
    for effect in hourly.attrs["effects"]:
        rows = hourly[
            (hourly["station"] == effect["station"]) & (hourly["quantity"] == effect["quantity"])
        ]
        values = np.abs(rows["static"].to_numpy())
        values = values[values > 0.0]
        fits = effect["fits"]
        assert fits["loaded_blocks"] == len(values) == 72
        gev, gumbel = fits["fits"]
        assert (gev["model"], gumbel["model"]) == ("gev", "gumbel")
        assert_same_gev({**gev["law"], "log_likelihood": gev["log_likelihood"]}, values)
        assert_same_gumbel(gumbel["law"], values)


def test_return_levels_are_scipy_s_quantiles_of_the_fitted_law(hourly):
    # The T-year level of hourly blocks with 250 days of traffic a year: the quantile of
    # (1 − 1/T)^(1/24/250) (docs/lifetime.md, "Return levels").
    for effect in hourly.attrs["effects"]:
        sign = -1.0 if effect["quantity"] == "deflection" else 1.0
        for fit in effect["fits"]["fits"]:
            law = fit["law"]
            for level in fit["return_levels"]:
                p = (1.0 - 1.0 / level["period_years"]) ** (1.0 / 24.0 / 250.0)
                want = scipy_stats.genextreme.ppf(p, -law["shape"], law["location"], law["scale"])
                assert sign * level["value"] == pytest.approx(want, rel=1e-9)


def test_the_profile_interval_s_ends_drop_the_likelihood_by_half_the_chi_square_point(hourly):
    # At each end z of the 95 % profile-likelihood interval, the likelihood maximised over
    # (μ, σ) with ξ solving z = μ + σ c(ξ) lies 3.8415/2 below the maximum: checked with
    # scipy's own optimiser and root finder (Coles 2001, §2.6.6).
    effect = next(e for e in hourly.attrs["effects"] if e["quantity"] == "bending_moment")
    rows = hourly[hourly["quantity"] == "bending_moment"]
    values = np.abs(rows["static"].to_numpy())
    gumbel = effect["fits"]["fits"][1]
    law = gumbel["law"]
    level = gumbel["return_levels"][1]
    p = (1.0 - 1.0 / level["period_years"]) ** (1.0 / 24.0 / 250.0)
    reduced = -np.log(-np.log(p))

    def profile(z):
        def negative(log_scale):
            scale = np.exp(log_scale[0])
            return -scipy_stats.gumbel_r.logpdf(values, z - scale * reduced, scale).sum()

        return -negative(tight(negative, [np.log(law["scale"])]))

    best = gumbel["log_likelihood"]
    for end in (level["low"], level["high"]):
        assert best - profile(end) == pytest.approx(3.841458820694124 / 2.0, abs=1e-6)


def test_vbi_lifetime_attrs_are_lifetime_json_and_fit_block_maxima_gives_the_same(hourly, tmp_path):
    out = tmp_path / "out"
    done = run_command("lifetime", str(HOURLY), "--out", str(out))
    assert done.returncode == 0, done.stderr
    written = read_json(out / "lifetime.json")
    assert [e["fits"] for e in written["effects"]] == [
        e["fits"] for e in hourly.attrs["effects"]
    ]
    effect = hourly.attrs["effects"][1]
    values = hourly[hourly["quantity"] == effect["quantity"]]["static"].to_numpy()
    again = vbi.fit_block_maxima(
        values,
        block_days=1.0 / 24.0,
        sense=1.0,
        return_periods_years=[100, 1000],
        days_per_year=250,
        bootstrap_resamples=400,
        seed=1,
    )
    assert again == effect["fits"]


def scipy_gpd(exceedances, threshold):
    """scipy's generalised Pareto maximum-likelihood fit with the threshold fixed, from the
    exponential fit (ξ = 0, σ = the mean exceedance), as (σ, ξ, log-likelihood)."""
    c, _, scale = scipy_stats.genpareto.fit(
        exceedances, 0.0, floc=threshold, scale=np.mean(exceedances - threshold), optimizer=tight
    )
    return scale, c, scipy_stats.genpareto.logpdf(exceedances, c, threshold, scale).sum()


@pytest.mark.parametrize("seed, shape", [(5, -0.3), (6, 0.0), (7, 0.2)])
def test_generalised_pareto_fits_of_known_laws_agree_with_scipy(seed, shape):
    threshold = 2.0e6
    values = scipy_stats.genpareto.rvs(
        shape, loc=threshold, scale=3.0e5, size=400, random_state=np.random.default_rng(seed)
    )
    fit = vbi.fit_extreme_value(values, "gpd", threshold=threshold)
    scale, c, log_likelihood = scipy_gpd(values, threshold)
    assert fit["location"] == threshold
    assert fit["log_likelihood"] >= log_likelihood - 1e-9 * abs(log_likelihood)
    assert fit["scale"] == pytest.approx(scale, rel=1e-5)
    assert fit["shape"] == pytest.approx(c, abs=1e-5)


def test_the_peaks_over_threshold_fit_of_vbi_lifetime_agrees_with_scipy(hourly):
    # lifetime.json's threshold is the 1001st largest event; its 1000 exceedances are not in
    # the frame (which holds block maxima), so the fit is checked through its log-likelihood:
    # no parameters near scipy's fit of the same law do better than vbi's, and the level is
    # scipy's quantile of the law at the Poisson return period's exceedance probability.
    for effect in hourly.attrs["effects"]:
        peaks = effect["peaks_over_threshold"]
        assert peaks["exceedances"] == 1000
        law = peaks["law"]
        rate = peaks["rate_per_year"]
        record_years = hourly.attrs["record_days"] / 250.0
        assert 2.9 / 250.0 < record_years <= 3.0 / 250.0
        assert rate == pytest.approx(1000 / record_years, rel=1e-12)
        sign = -1.0 if effect["quantity"] == "deflection" else 1.0
        for level in peaks["return_levels"]:
            r = rate / -np.log1p(-1.0 / level["period_years"])
            want = scipy_stats.genpareto.ppf(1.0 - 1.0 / r, law["shape"], law["threshold"], law["scale"])
            assert sign * level["value"] == pytest.approx(want, rel=1e-9)
            assert abs(level["low"]) < abs(level["value"]) < abs(level["high"])


def test_lifetime_return_levels_is_the_command_s_return_levels_csv(hourly, tmp_path):
    import pandas as pd

    out = tmp_path / "out"
    done = run_command("lifetime", str(HOURLY), "--out", str(out))
    assert done.returncode == 0, done.stderr
    written = pd.read_csv(out / "return_levels.csv")
    frame = vbi.lifetime_return_levels(hourly)
    assert list(frame.columns) == list(written.columns)
    assert len(frame) == len(written) == 18
    pd.testing.assert_frame_equal(frame, written, check_exact=True, check_dtype=False)


def test_a_fit_refuses_too_few_block_maxima_with_the_library_s_message():
    with pytest.raises(vbi.VbiError, match="too few to fit"):
        vbi.fit_extreme_value([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="block_days"):
        vbi.fit_block_maxima(list(range(1, 20)), block_days=0.0)
    # The lifetime file's limits: a return period above 10⁶ years is refused, as in TOML.
    with pytest.raises(ValueError, match="return period"):
        vbi.fit_block_maxima(list(range(1, 20)), return_periods_years=[1e17])
