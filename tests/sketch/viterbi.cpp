#include "sketch/viterbi.h"

#include "core/error.h"
#include "core/random.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;
using namespace facesketch::sketch;

TEST_CASE("viterbi: the path and its log probability match brute force on small random trellises")
{
    Random random(3);
    auto u = [&] { return random.uniform(-4.0, 0.0); };
    for (int trial = 0; trial < 50; ++trial) {
        const int n = 1 + trial % 5;
        std::vector<int> sizes;
        for (int i = 0; i < n; ++i)
            sizes.push_back(1 + static_cast<int>(random.index(4)));
        Eigen::VectorXd initial(sizes[0]);
        for (int j = 0; j < sizes[0]; ++j)
            initial[j] = u();
        std::vector<Eigen::VectorXd> emission(static_cast<std::size_t>(n));
        std::vector<Eigen::MatrixXd> transition(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            emission[static_cast<std::size_t>(i)] = Eigen::VectorXd::NullaryExpr(sizes[static_cast<std::size_t>(i)], [&] { return u(); });
            if (i > 0) {
                transition[static_cast<std::size_t>(i)] = Eigen::MatrixXd::NullaryExpr(
                    sizes[static_cast<std::size_t>(i - 1)], sizes[static_cast<std::size_t>(i)], [&] { return u(); });
                // Some impossible transitions.
                if (trial % 3 == 0)
                    transition[static_cast<std::size_t>(i)](0, 0) = -INFINITY;
            }
        }
        // Brute force over every path.
        double best = -INFINITY;
        std::vector<int> bestPath;
        std::vector<int> path(static_cast<std::size_t>(n), 0);
        while (true) {
            double lp = initial[path[0]] + emission[0][path[0]];
            for (int i = 1; i < n; ++i)
                lp += transition[static_cast<std::size_t>(i)](path[static_cast<std::size_t>(i - 1)], path[static_cast<std::size_t>(i)])
                    + emission[static_cast<std::size_t>(i)][path[static_cast<std::size_t>(i)]];
            if (lp > best) {
                best = lp;
                bestPath = path;
            }
            int i = n - 1;
            while (i >= 0 && ++path[static_cast<std::size_t>(i)] == sizes[static_cast<std::size_t>(i)])
                path[static_cast<std::size_t>(i--)] = 0;
            if (i < 0)
                break;
        }
        const ViterbiPath v = viterbi(initial, emission, transition);
        INFO("trial " << trial);
        if (bestPath.empty()) { // every path impossible (a size-1 layer after a size-1 layer)
            REQUIRE(std::isinf(v.logProbability));
            REQUIRE(v.states.size() == static_cast<std::size_t>(n));
            continue;
        }
        REQUIRE(v.logProbability == Approx(best).epsilon(1e-12));
        REQUIRE(v.states == bestPath);
    }
}

TEST_CASE("viterbi: ties pick the lowest indices, impossible trellises still give a path, bad shapes are named")
{
    // Two equally good paths: (0, 1) and (1, 0); the lowest previous state wins the max at each
    // state, the lowest final state at the end.
    const Eigen::VectorXd initial = Eigen::VectorXd::Zero(2);
    const std::vector<Eigen::VectorXd> emission = { Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2) };
    Eigen::MatrixXd t(2, 2);
    t << -1, 0, 0, -1;
    const ViterbiPath v = viterbi(initial, emission, { Eigen::MatrixXd(), t });
    CHECK(v.states == std::vector<int> { 1, 0 }); // final state 0 (lowest), reached from 1
    CHECK(v.logProbability == 0);

    Eigen::MatrixXd none = Eigen::MatrixXd::Constant(2, 2, -INFINITY);
    const ViterbiPath dead = viterbi(initial, emission, { Eigen::MatrixXd(), none });
    CHECK(dead.states == std::vector<int> { 0, 0 });
    CHECK(std::isinf(dead.logProbability));

    REQUIRE_THROWS_WITH(viterbi(initial, {}, std::vector<Eigen::MatrixXd> {}), Catch::Contains("no layers"));
    REQUIRE_THROWS_WITH(viterbi(initial, { Eigen::VectorXd::Zero(2), Eigen::VectorXd() }, { Eigen::MatrixXd(), Eigen::MatrixXd(2, 0) }),
        Catch::Contains("layer 1 has no states"));
    REQUIRE_THROWS_WITH(
        viterbi(initial, emission, { Eigen::MatrixXd(), Eigen::MatrixXd::Zero(3, 2) }), Catch::Contains("transition 1 is 3 by 2"));
    REQUIRE_THROWS_WITH(viterbi(Eigen::VectorXd::Zero(3), emission, { Eigen::MatrixXd(), t }), Catch::Contains("3 initial values"));
    // A transition made on demand that leaves the asked shape is refused the same way.
    const TransitionFn reshaping = [](std::size_t, Eigen::MatrixXd& out) { out = Eigen::MatrixXd::Zero(2, 1); };
    REQUIRE_THROWS_WITH(
        viterbi(initial, emission, reshaping), Catch::Contains("transition 1 is 2 by 1, layers 0 and 1 have 2 and 2 states"));
}
