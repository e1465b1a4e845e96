#pragma once
// The Viterbi algorithm (thesis 4.8.2; Bishop 2006, 13.2.5) in log space over a trellis whose
// layers have their own state sets: layer i has m_i states (a stroke point's candidates), so a
// transition is an m_{i-1} by m_i matrix and the whole run costs O(sum m_{i-1} m_i), i.e.
// O(n m^2) for n layers of at most m states, never one M x M matrix over all states.
//
// Log probabilities may be -infinity (impossible). Ties are broken deterministically: the
// lowest previous-state index in every max, the lowest final-state index at the end.

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace facesketch::sketch {

struct ViterbiPath {
    std::vector<int> states; ///< per layer, the chosen state's index in that layer
    double logProbability = 0;
};

/// logInitial: m_0 values; logEmission[i]: m_i values; logTransition[i] for i >= 1: m_{i-1} by
/// m_i (row: previous state, column: next state); logTransition[0] is ignored. Throws Error
/// naming the layer for an empty layer or a mismatched size. If every path is impossible, the
/// result is still a path (the last layer's state 0 and its back pointers) with logProbability
/// -infinity.
ViterbiPath viterbi(
    const Eigen::VectorXd& logInitial, const std::vector<Eigen::VectorXd>& logEmission, const std::vector<Eigen::MatrixXd>& logTransition);

/// The same, with each transition matrix made on demand: `transition(i, out)` fills `out`
/// (m_{i-1} by m_i, already sized) for layer i >= 1, so memory stays O(n m + m^2) for long
/// strokes. Throws Error naming the layer if `transition` leaves `out` in another shape.
using TransitionFn = std::function<void(std::size_t layer, Eigen::MatrixXd& logTransition)>;
ViterbiPath viterbi(const Eigen::VectorXd& logInitial, const std::vector<Eigen::VectorXd>& logEmission, const TransitionFn& transition);

} // namespace facesketch::sketch
