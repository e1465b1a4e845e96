#pragma once
// How sure a figure measured on a few held-out faces is. `eval strokes` and `eval observe`
// report a ratio of two means over the same faces (the reconstruction's error over the mean
// face's); with 20 test faces that ratio moves by several hundredths with the draw of the faces
// alone (docs/sketching.md, "How sure the figures are"), so a change smaller than its interval
// is not a finding, and a bar such as issue 12's 0.45 is met only when the interval lies under it.
//
// The interval is the percentile bootstrap (Efron and Tibshirani, "An Introduction to the
// Bootstrap", 1993, ch. 13): the faces are drawn with replacement as many times as there are
// faces, the ratio of the sums recomputed, `resamples` times; the 2.5th and 97.5th percentiles
// of those ratios bound it. Faces, not vertices, are the unit: a face's vertices are far from
// independent. Deterministic for a seed (core/random.h).

#include <cstdint>
#include <vector>

namespace facesketch::evaluation {

struct Interval {
    double low = 0, high = 0;
};

/// The 95% percentile-bootstrap interval of sum(numerators) / sum(denominators), one entry of
/// each per face. Throws Error for sizes that differ, no faces, fewer than 100 resamples, a
/// value that is not finite, a negative denominator or denominators summing to 0 (whose
/// ratio means nothing). One face gives the ratio itself at both ends.
Interval bootstrapRatio(
    const std::vector<double>& numerators, const std::vector<double>& denominators, int resamples = 2000, std::uint64_t seed = 1);

/// The 95% interval of the difference of two ratios over the same faces and denominators,
/// (sum(a) - sum(b)) / sum(denominators): two mappers scored on the same test faces against the
/// same mean-face errors. The faces are resampled in pairs, so what makes one face hard for both
/// cancels; two ratios whose own intervals overlap can still differ beyond doubt when one is
/// lower on nearly every face. Throws as bootstrapRatio, and for `a` and `b` of other sizes.
Interval bootstrapRatioDifference(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& denominators,
    int resamples = 2000, std::uint64_t seed = 1);

} // namespace facesketch::evaluation
