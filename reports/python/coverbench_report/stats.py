"""Statistics for reports: every test and interval comes from scipy.stats; what is computed here
is only the bookkeeping around them (pairing, tie bands, Holm's step-down, profile ratios)."""
import math

import numpy as np
from scipy import stats

ALPHA = 0.05
# Two order statistics further apart than this many places have no draw between them with
# probability under (1 - 63/n)^n < e^-63 < 1e-27: far below a double's rounding of the 2.5 % tail.
_MEDIAN_GAP = 64


def wilson(successes, trials, confidence=0.95):
    """Wilson score interval of a proportion (scipy.stats.binomtest)."""
    if trials == 0:
        return (math.nan, math.nan)
    ci = stats.binomtest(successes, trials).proportion_ci(confidence_level=confidence, method="wilson")
    return (float(ci.low), float(ci.high))


def _binom_sf(k, n, p):
    """P(Binomial(n, p) > k), elementwise over p."""
    return stats.binom.sf(k, n, p)


def median_bootstrap(sorted_values):
    """The bootstrap distribution of the sample median, exactly: no resampling, so no seed.

    A resample draws n of the n values with replacement; its median is a function of which
    sorted places the draws land on, and how many land at or below a place is binomial. With
    n = 2m + 1 the median is the draws' (m+1)-th smallest: P(median <= x_(j)) = P(Bin(n, j/n) > m).
    With n = 2m it is the mean of the m-th and (m+1)-th smallest, at places i <= j:
      i < j: exactly m draws at or below i with one at i, the other n - m at or above j with one
             at j: C(n, m) [(i/n)^m - ((i-1)/n)^m] [((n-j+1)/n)^(n-m) - ((n-j)/n)^(n-m)];
      i = j: fewer than m draws below i and fewer than n - m above it (inclusion-exclusion over
             the two binomials; both can only fail together as m below, n - m above, none at i).
    Pairs over 64 places apart are left out (their mass is under 1e-27, see _MEDIAN_GAP).
    Returns (support, probabilities): the medians' values in increasing order, each once."""
    x = np.asarray(sorted_values, dtype=float)
    n = len(x)
    places = np.arange(1, n + 1, dtype=float)
    if n % 2:
        m = n // 2
        cdf = _binom_sf(m, n, places / n)
        cdf[-1] = 1.0
        mass = np.diff(cdf, prepend=0.0)
        values = x
    else:
        m = n // 2
        log_c = math.lgamma(n + 1) - 2 * math.lgamma(m + 1)
        i = places[:, None]
        gap = np.arange(1, min(_MEDIAN_GAP, n - 1) + 1, dtype=float)[None, :]
        j = i + gap
        keep = j <= n
        jj = np.where(keep, j, n)
        with np.errstate(divide="ignore", invalid="ignore"):
            low = m * np.log(i / n) + np.log(-np.expm1(m * np.log1p(-1.0 / i)))
            above = n - jj + 1
            high = (n - m) * np.log(above / n) + np.log(-np.expm1((n - m) * np.log1p(-1.0 / above)))
            apart = np.where(keep, np.exp(log_c + low + high), 0.0)
            below, beyond = (places - 1) / n, (n - places) / n
            ends = np.exp(log_c + m * np.log(below) + (n - m) * np.log(beyond))
        same = 1.0 - _binom_sf(m - 1, n, below) - _binom_sf(n - m - 1, n, beyond) + ends
        ii = np.broadcast_to(i, j.shape)[keep].astype(int) - 1
        values = np.concatenate([x, (x[ii] + x[jj[keep].astype(int) - 1]) / 2])
        mass = np.concatenate([np.clip(same, 0.0, 1.0), apart[keep]])
    order = np.argsort(values, kind="stable")
    values, mass = values[order], mass[order]
    support, first = np.unique(values, return_index=True)
    return support, np.add.reduceat(mass, first)


def median_interval(sorted_values, confidence=0.95):
    """The percentile bootstrap interval of the median from its exact bootstrap distribution: the
    smallest medians whose probability of not being exceeded reaches (1 - confidence) / 2 and
    (1 + confidence) / 2 (what the resampled percentile interval tends to as resamples grow)."""
    support, mass = median_bootstrap(sorted_values)
    cdf = np.cumsum(mass)
    cdf /= cdf[-1]  # the left-out pairs and rounding: a total of 1 within 1e-15
    tail = (1.0 - confidence) / 2
    lo = int(np.searchsorted(cdf, tail - 1e-12, side="left"))
    hi = int(np.searchsorted(cdf, 1.0 - tail - 1e-12, side="left"))
    return float(support[lo]), float(support[min(hi, len(support) - 1)])


def holm(pvalues):
    """Holm's step-down adjusted p-values, in the input order (NaN stays NaN, not counted)."""
    indexed = [(p, i) for i, p in enumerate(pvalues) if not math.isnan(p)]
    indexed.sort()
    m = len(indexed)
    adjusted = [math.nan] * len(pvalues)
    running = 0.0
    for rank, (p, i) in enumerate(indexed):
        running = max(running, min(1.0, (m - rank) * p))
        adjusted[i] = running
    return adjusted


def tied(spec, a, b):
    """Whether two values are equal within the metric's tie band (same rule as the C++ registry)."""
    if a == b:
        return True
    if not (math.isfinite(a) and math.isfinite(b)):  # a failure (infinite) ties nothing but a failure
        return False
    return abs(a - b) <= spec["tie_absolute"] + spec["tie_relative"] * max(abs(a), abs(b))


def paired(spec, values, baseline):
    """Paired comparison of `values` against `baseline` (equal-length lists, one pair per wall).

    A failure (no valid path) is the metric's worst value, infinite (analysis.Analysis.pairs): it
    loses to every value. Returns pairs, wins/ties/losses (better = the metric's direction, ties
    within its band), `failed` and `baseline_failed` (pairs where that side failed), the median
    difference (values - baseline) with the percentile bootstrap 95 % interval of the median over
    the pairs where both have a value (`both`; median_interval: exact, no resampling), and the two-sided Wilcoxon signed-rank p-value over the pairs that
    are not tied (1 when all are), a failure's difference ranked above every finite one (failures
    share the largest rank)."""
    a = np.asarray(values, dtype=float)
    b = np.asarray(baseline, dtype=float)
    n = len(a)
    out = {"pairs": n, "wins": 0, "ties": 0, "losses": 0, "failed": int((~np.isfinite(a)).sum()),
           "baseline_failed": int((~np.isfinite(b)).sum()), "both": 0, "median": math.nan, "low": math.nan,
           "high": math.nan, "p": math.nan}
    if n == 0:
        return out
    finite = np.isfinite(a) & np.isfinite(b)
    with np.errstate(invalid="ignore"):
        diff = a - b  # +-inf where one side failed (never both: such walls are not pairs)
    tie = np.array([tied(spec, x, y) for x, y in zip(a, b)])
    better = spec["better"]
    out["ties"] = int(tie.sum())
    out["wins"] = int(((diff * better > 0) & ~tie).sum())
    out["losses"] = int(((diff * better < 0) & ~tie).sum())
    both = diff[finite]
    out["both"] = int(len(both))
    if len(both):
        out["median"] = float(np.median(both))
    if len(both) >= 2 and np.ptp(both) > 0:
        # A function of the sorted differences: not of the order the pairs were read in.
        out["low"], out["high"] = median_interval(np.sort(both))
    else:
        out["low"] = out["high"] = out["median"]
    untied = diff[~tie]
    if len(untied) == 0:
        out["p"] = 1.0
    else:
        # Only the ranks of |difference| matter: a failure's stands above every finite one.
        big = 2.0 * float(np.max(np.abs(untied[np.isfinite(untied)]), initial=0.0)) + 1.0
        untied = np.where(np.isfinite(untied), untied, np.sign(untied) * big)
        out["p"] = float(stats.wilcoxon(untied, zero_method="wilcox", alternative="two-sided").pvalue)
    return out


def nemenyi_cd(k, blocks, alpha=ALPHA):
    """Nemenyi's critical difference of average ranks for k treatments over `blocks` blocks
    (Demsar 2006): q_alpha / sqrt(2) * sqrt(k (k + 1) / (6 N)), q from the studentized range."""
    q = stats.studentized_range.ppf(1 - alpha, k, np.inf) / math.sqrt(2)
    return float(q * math.sqrt(k * (k + 1) / (6.0 * blocks)))


def friedman(spec, table):
    """Friedman test over a blocks x treatments table (rows: walls, columns: planners).

    Returns the statistic, p-value, the average ranks (1 = best in the metric's direction, ties
    averaged) and Nemenyi's critical difference."""
    data = np.asarray(table, dtype=float)
    n, k = data.shape
    oriented = -data * spec["better"]  # smaller is better after orientation
    ranks = np.apply_along_axis(stats.rankdata, 1, oriented)
    out = {"blocks": n, "k": k, "ranks": [float(r) for r in ranks.mean(axis=0)], "statistic": math.nan,
           "p": math.nan, "cd": math.nan}
    if n < 2 or k < 3:
        return out
    if np.all(data == data[:, :1]):
        out["statistic"], out["p"] = 0.0, 1.0
    else:
        res = stats.friedmanchisquare(*[data[:, j] for j in range(k)])
        out["statistic"], out["p"] = float(res.statistic), float(res.pvalue)
    out["cd"] = nemenyi_cd(k, n)
    return out


def performance_profile(costs, taus):
    """Dolan-More performance profiles. `costs`: problems x solvers, inf for a failure.

    rho_s(tau) = share of problems where solver s's cost is within tau times the best cost.
    A problem every solver failed counts against all of them."""
    c = np.asarray(costs, dtype=float)
    best = np.min(c, axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(np.isfinite(c), c / best, np.inf)
    ratio[~np.isfinite(best[:, 0]), :] = np.inf
    return np.array([[float(np.mean(ratio[:, s] <= t)) for t in taus] for s in range(c.shape[1])]), ratio


def power_law(x, y):
    """Least-squares fit of log y = a + b log x (scipy.stats.linregress): exponent b, its
    standard error and r; None with fewer than 3 distinct x."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if len(np.unique(x[keep])) < 3:
        return None
    r = stats.linregress(np.log10(x[keep]), np.log10(y[keep]))
    return {"exponent": float(r.slope), "stderr": float(r.stderr), "intercept": float(r.intercept),
            "r": float(r.rvalue), "n": int(keep.sum())}


def geometric_mean_ci(log_ratios, confidence=0.95):
    """Geometric mean of ratios from their logarithms, with a t-interval on the mean log ratio
    (scipy.stats.t), taken back by exp: (mean, low, high). One ratio gives no interval (NaN); equal
    ratios give an interval of width zero."""
    x = np.asarray(log_ratios, dtype=float)
    n = len(x)
    if n == 0:
        return (math.nan, math.nan, math.nan)
    mean = float(np.mean(x))
    if n == 1:
        return (_exp(mean), math.nan, math.nan)
    half = float(stats.t.ppf(0.5 + confidence / 2, n - 1)) * float(np.std(x, ddof=1)) / math.sqrt(n)
    return (_exp(mean), _exp(mean - half), _exp(mean + half))


def _exp(v):
    """e^v, infinity past the largest double (a ratio of over 1e308)."""
    try:
        return math.exp(v)
    except OverflowError:
        return math.inf


def signed_rank(log_ratios):
    """Two-sided Wilcoxon signed-rank p-value of log ratios against 0 (scipy.stats.wilcoxon);
    NaN without any, 1 when every ratio is 1."""
    x = np.asarray(log_ratios, dtype=float)
    if len(x) == 0:
        return math.nan
    if np.all(x == 0):
        return 1.0
    return float(stats.wilcoxon(x, zero_method="wilcox", alternative="two-sided").pvalue)
