#include "sketch/viterbi.h"

#include "core/error.h"

#include <limits>

namespace facesketch::sketch {

ViterbiPath viterbi(
    const Eigen::VectorXd& logInitial, const std::vector<Eigen::VectorXd>& logEmission, const std::vector<Eigen::MatrixXd>& logTransition)
{
    const std::size_t n = logEmission.size();
    if (logTransition.size() != n)
        fail("viterbi: ", n, " emission layers but ", logTransition.size(), " transition layers");
    // Each matrix's shape is checked by the general form, after the copy.
    return viterbi(logInitial, logEmission, [&](std::size_t i, Eigen::MatrixXd& out) { out = logTransition[i]; });
}

ViterbiPath viterbi(const Eigen::VectorXd& logInitial, const std::vector<Eigen::VectorXd>& logEmission, const TransitionFn& transition)
{
    const std::size_t n = logEmission.size();
    if (n == 0)
        fail("viterbi: no layers");
    if (logInitial.size() != logEmission[0].size())
        fail("viterbi: ", logInitial.size(), " initial values for layer 0 of ", logEmission[0].size(), " states");
    for (std::size_t i = 0; i < n; ++i)
        if (logEmission[i].size() == 0)
            fail("viterbi: layer ", i, " has no states");
    Eigen::MatrixXd logTransition;
    const double minusInf = -std::numeric_limits<double>::infinity();
    // score: best log probability of a path ending in each state of the current layer.
    Eigen::VectorXd score = logInitial + logEmission[0];
    std::vector<std::vector<int>> back(n);
    for (std::size_t i = 1; i < n; ++i) {
        const Eigen::Index m = logEmission[i].size();
        logTransition.resize(score.size(), m);
        transition(i, logTransition);
        // The loop below reads the matrix through plain pointers: a transition that changed its
        // shape is refused, not read out of bounds.
        if (logTransition.rows() != score.size() || logTransition.cols() != m)
            fail("viterbi: transition ", i, " is ", logTransition.rows(), " by ", logTransition.cols(), ", layers ", i - 1, " and ", i,
                " have ", score.size(), " and ", m, " states");
        Eigen::VectorXd next(m);
        back[i].assign(static_cast<std::size_t>(m), 0);
        // Plain pointers in the O(m^2) loop: a column of the transition is contiguous, and
        // Eigen's checked element access would cost more than the sum in the debug builds.
        const double* from = score.data();
        const Eigen::Index rows = score.size();
        for (Eigen::Index q = 0; q < m; ++q) {
            const double* column = logTransition.col(q).data();
            double best = minusInf;
            int arg = 0;
            for (Eigen::Index j = 0; j < rows; ++j) {
                const double s = from[j] + column[j];
                if (s > best) { // strict: the lowest index wins a tie
                    best = s;
                    arg = static_cast<int>(j);
                }
            }
            next[q] = best + logEmission[i][q];
            back[i][static_cast<std::size_t>(q)] = arg;
        }
        score.swap(next);
    }
    ViterbiPath path;
    path.states.assign(n, 0);
    double best = minusInf;
    int arg = 0;
    for (Eigen::Index q = 0; q < score.size(); ++q)
        if (score[q] > best) {
            best = score[q];
            arg = static_cast<int>(q);
        }
    path.logProbability = best;
    path.states[n - 1] = arg;
    for (std::size_t i = n - 1; i > 0; --i)
        path.states[i - 1] = back[i][static_cast<std::size_t>(path.states[i])];
    return path;
}

} // namespace facesketch::sketch
