#include "evaluation/interval.h"

#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>

namespace facesketch::evaluation {

Interval bootstrapRatio(const std::vector<double>& numerators, const std::vector<double>& denominators, int resamples, std::uint64_t seed)
{
    if (numerators.size() != denominators.size())
        fail("bootstrapRatio: ", numerators.size(), " numerators but ", denominators.size(), " denominators");
    if (numerators.empty())
        fail("bootstrapRatio: no faces");
    if (resamples < 100)
        fail("bootstrapRatio: ", resamples, " resamples, fewer than 100 cannot place a 2.5th percentile");
    double denominator = 0;
    for (size_t i = 0; i < numerators.size(); ++i) {
        if (!std::isfinite(numerators[i]) || !std::isfinite(denominators[i]))
            fail("bootstrapRatio: face ", i, " has a value that is not finite (", numerators[i], " / ", denominators[i], ")");
        if (denominators[i] < 0)
            fail("bootstrapRatio: face ", i, " has a negative denominator ", denominators[i]);
        denominator += denominators[i];
    }
    if (denominator <= 0)
        fail("bootstrapRatio: the denominators sum to 0");

    const auto n = static_cast<std::int64_t>(numerators.size());
    Random random(seed);
    std::vector<double> ratios;
    ratios.reserve(static_cast<size_t>(resamples));
    for (int r = 0; r < resamples; ++r) {
        double a = 0, b = 0;
        for (std::int64_t k = 0; k < n; ++k) {
            const auto i = static_cast<size_t>(random.index(n));
            a += numerators[i];
            b += denominators[i];
        }
        // A resample of faces whose denominators are all 0 has no ratio; it is drawn again.
        if (b > 0)
            ratios.push_back(a / b);
        else
            --r;
    }
    std::sort(ratios.begin(), ratios.end());
    const auto at = [&](double q) {
        // The empirical quantile with linear interpolation between order statistics.
        const double x = q * static_cast<double>(ratios.size() - 1);
        const auto i = static_cast<size_t>(std::floor(x));
        const size_t j = std::min(i + 1, ratios.size() - 1);
        return ratios[i] + (x - static_cast<double>(i)) * (ratios[j] - ratios[i]);
    };
    return { at(0.025), at(0.975) };
}

Interval bootstrapRatioDifference(
    const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& denominators, int resamples, std::uint64_t seed)
{
    if (a.size() != b.size())
        fail("bootstrapRatioDifference: ", a.size(), " values of the first ratio but ", b.size(), " of the second");
    // The difference of the ratios is one ratio whose numerators are the faces' differences
    // (which may be negative; only the denominators must not be).
    std::vector<double> differences(a.size());
    for (size_t i = 0; i < a.size(); ++i)
        differences[i] = a[i] - b[i];
    return bootstrapRatio(differences, denominators, resamples, seed);
}

} // namespace facesketch::evaluation
