#include "tools/metrics/assignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

namespace slammtt {
namespace {

const double kInf = kForbiddenCost;

// Every partial injection of rows into columns, keeping the one with the most allowed pairs and
// then the least cost: the definition the solver must meet.
std::pair<int, double> BruteForce(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  int best_count = 0;
  double best_cost = 0.0;
  std::vector<bool> used(cols, false);
  std::function<void(int, int, double)> recurse = [&](int row, int count, double sum) {
    if (row == rows) {
      if (count > best_count || (count == best_count && sum < best_cost)) {
        best_count = count;
        best_cost = sum;
      }
      return;
    }
    recurse(row + 1, count, sum);  // row left unassigned
    for (int j = 0; j < cols; ++j) {
      if (used[j] || cost(row, j) == kInf) continue;
      used[j] = true;
      recurse(row + 1, count + 1, sum + cost(row, j));
      used[j] = false;
    }
  };
  recurse(0, 0, 0.0);
  return {best_count, best_cost};
}

void ExpectConsistent(const Eigen::MatrixXd& cost, const Assignment& a) {
  ASSERT_EQ(a.row_to_col.size(), static_cast<size_t>(cost.rows()));
  ASSERT_EQ(a.col_to_row.size(), static_cast<size_t>(cost.cols()));
  int count = 0;
  double sum = 0.0;
  for (int i = 0; i < cost.rows(); ++i) {
    const int j = a.row_to_col[i];
    if (j < 0) continue;
    ASSERT_LT(j, cost.cols());
    EXPECT_EQ(a.col_to_row[j], i);
    EXPECT_NE(cost(i, j), kInf);
    ++count;
    sum += cost(i, j);
  }
  EXPECT_EQ(count, a.num_assigned);
  EXPECT_NEAR(sum, a.total_cost, 1e-12);
}

TEST(AssignmentTest, SolvesSquareTextbookCase) {
  Eigen::MatrixXd cost(3, 3);
  cost << 4, 1, 3,
          2, 0, 5,
          3, 2, 2;
  const Assignment a = SolveMinCostAssignment(cost);
  ExpectConsistent(cost, a);
  EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 0, 2}));
  EXPECT_DOUBLE_EQ(a.total_cost, 5.0);
}

TEST(AssignmentTest, SolvesWideAndTallMatrices) {
  Eigen::MatrixXd wide(2, 4);
  wide << 9, 2, 7, 8,
          6, 4, 3, 7;
  const Assignment a = SolveMinCostAssignment(wide);
  ExpectConsistent(wide, a);
  EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 2}));
  EXPECT_DOUBLE_EQ(a.total_cost, 5.0);

  const Eigen::MatrixXd tall = wide.transpose();
  const Assignment b = SolveMinCostAssignment(tall);
  ExpectConsistent(tall, b);
  EXPECT_EQ(b.col_to_row, (std::vector<int>{1, 2}));
  EXPECT_EQ(b.row_to_col, (std::vector<int>{-1, 0, 1, -1}));
  EXPECT_DOUBLE_EQ(b.total_cost, 5.0);
}

TEST(AssignmentTest, PrefersMorePairsOverLowerCost) {
  // Alone, (0,0) = 0.1 is the cheapest pair; but two pairs (0,1) + (1,0) fit the threshold.
  Eigen::MatrixXd cost(2, 2);
  cost << 0.1, 0.9,
          0.2, kInf;
  const Assignment a = SolveMinCostAssignment(cost);
  ExpectConsistent(cost, a);
  EXPECT_EQ(a.num_assigned, 2);
  EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 0}));
  EXPECT_NEAR(a.total_cost, 1.1, 1e-12);
}

TEST(AssignmentTest, EmptyAndAllForbiddenAssignNothing) {
  for (const Eigen::MatrixXd& cost :
       {Eigen::MatrixXd(0, 0), Eigen::MatrixXd(0, 3), Eigen::MatrixXd(2, 0),
        Eigen::MatrixXd(Eigen::MatrixXd::Constant(2, 3, kInf))}) {
    const Assignment a = SolveMinCostAssignment(cost);
    ExpectConsistent(cost, a);
    EXPECT_EQ(a.num_assigned, 0);
    EXPECT_EQ(a.total_cost, 0.0);
    EXPECT_TRUE(std::all_of(a.row_to_col.begin(), a.row_to_col.end(),
                            [](int j) { return j == -1; }));
  }
}

TEST(AssignmentTest, RejectsNegativeAndNaNCosts) {
  Eigen::MatrixXd negative = Eigen::MatrixXd::Ones(2, 2);
  negative(1, 0) = -0.5;
  EXPECT_THROW(SolveMinCostAssignment(negative), std::invalid_argument);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Ones(2, 2);
  nan(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SolveMinCostAssignment(nan), std::invalid_argument);
}

TEST(AssignmentTest, MatchesBruteForceOnRandomSmallMatrices) {
  std::mt19937_64 rng(20240611);
  std::uniform_int_distribution<int> size(1, 6);
  std::uniform_real_distribution<double> value(0.0, 10.0);
  std::bernoulli_distribution forbidden(0.3);
  std::uniform_int_distribution<int> small_integer(0, 3);  // many ties
  for (int trial = 0; trial < 400; ++trial) {
    Eigen::MatrixXd cost(size(rng), size(rng));
    for (Eigen::Index i = 0; i < cost.rows(); ++i) {
      for (Eigen::Index j = 0; j < cost.cols(); ++j) {
        const double v = trial % 2 == 0 ? value(rng) : small_integer(rng);
        cost(i, j) = forbidden(rng) ? kInf : v;
      }
    }
    const Assignment a = SolveMinCostAssignment(cost);
    ExpectConsistent(cost, a);
    const auto [best_count, best_cost] = BruteForce(cost);
    EXPECT_EQ(a.num_assigned, best_count) << "trial " << trial << "\n" << cost;
    EXPECT_NEAR(a.total_cost, best_cost, 1e-9) << "trial " << trial << "\n" << cost;
  }
}

}  // namespace
}  // namespace slammtt
