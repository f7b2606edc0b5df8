// Relocalisation votes (relocalisation.h): the prediction of one relocalisation through another
// and the odometry inside the two pieces, and joining two pieces only when votes agree.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/relocalisation.h"

namespace {

using gasp::Isometry3;
using gasp::PoseConstraint;

/// Frame i of a turning path: x = 0.2 i, turning 7 deg per frame about y, rolling 20 deg about z.
Isometry3 truth(std::size_t i) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = (Eigen::AngleAxisd(0.12 * i, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(0.35 * i, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.2 * i, 0.03 * i * i, 0.1);
  return T;
}

/// An exact constraint from -> to with standard deviations 1 cm and 0.01 rad (or `error` applied).
PoseConstraint constraint(std::size_t from, std::size_t to, const Isometry3& error = Isometry3::Identity()) {
  PoseConstraint c;
  c.from = from;
  c.to = to;
  c.T_from_to = error * truth(from).inverse() * truth(to);
  c.information = gasp::Matrix6d::Identity() * 1e4;
  return c;
}

/// Two pieces of odometry: 0 -> 1 -> ... -> 4 and 5 -> 6 -> ... -> 9 (nothing ends in 5), and
/// a third piece 10 -> 11.
std::vector<PoseConstraint> odometry() {
  std::vector<PoseConstraint> tree;
  for (std::size_t i = 0; i < 4; ++i) tree.push_back(constraint(i, i + 1));
  for (std::size_t i = 5; i < 9; ++i) tree.push_back(constraint(i, i + 1));
  tree.push_back(constraint(10, 11));
  return tree;
}

Isometry3 shifted(double metres) {
  Isometry3 T = Isometry3::Identity();
  T.translation() = Eigen::Vector3d(metres, 0, 0);
  return T;
}

}  // namespace

TEST(RelocalisationPrediction, ThroughTheOdometryOfBothPieces) {
  const auto tree = odometry();
  // 2 -> 8 predicted through 1 -> 6: 2 -> 1 (1 edge), 1 -> 6, 6 -> 8 (2 edges).
  const auto p = gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 2, 8);
  ASSERT_TRUE(p.has_value());
  EXPECT_TRUE(p->T_a_b.isApprox(truth(2).inverse() * truth(8), 1e-9));
  EXPECT_EQ(p->edges, 4u);
  // The covariance grows with the path and stays symmetric positive definite.
  const auto shorter = gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 1, 6);
  ASSERT_TRUE(shorter.has_value());
  EXPECT_TRUE(shorter->covariance.isApprox(gasp::Matrix6d::Identity() * 1e-4, 1e-9));
  EXPECT_GT(p->covariance.trace(), shorter->covariance.trace());
  EXPECT_TRUE(p->covariance.isApprox(p->covariance.transpose(), 1e-12));
  EXPECT_EQ(Eigen::LLT<gasp::Matrix6d>(p->covariance).info(), Eigen::Success);
  // The other way round: 7 -> 3 through 1 -> 6 (inverted).
  const auto back = gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 7, 3);
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(back->T_a_b.isApprox(truth(7).inverse() * truth(3), 1e-9));
  // Not the pieces the relocalisation links, or a frame out of range.
  EXPECT_FALSE(gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 2, 11).has_value());
  EXPECT_FALSE(gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 2, 3).has_value());
  EXPECT_THROW(gasp::predictThroughRelocalisation(tree, 12, constraint(1, 6), 2, 40), gasp::Error);
  PoseConstraint singular = constraint(1, 6);
  singular.information.setZero();
  EXPECT_THROW(gasp::predictThroughRelocalisation(tree, 12, singular, 2, 8), gasp::Error);
}

TEST(RelocalisationPrediction, EqualsTheCompositionAlongTheTreeTheVoteCompletes) {
  // With the vote as one more edge the odometry stays a tree (it ends in a piece's first frame),
  // so composeAlongTree gives the same pose and covariance -- either way round.
  auto tree = odometry();
  for (std::size_t i = 0; i < tree.size(); ++i)  // unequal covariances, so a missing adjoint shows
    tree[i].information = gasp::Matrix6d(gasp::Vector6d(1e4, 2e4, 5e3, 1e5, 3e4, 2e5).asDiagonal()) * (1.0 + i);
  for (const PoseConstraint& h : {constraint(1, 5), constraint(7, 0)}) {
    PoseConstraint vote = h;
    vote.information = gasp::Matrix6d(gasp::Vector6d(4e3, 1e4, 2e4, 5e4, 1e5, 7e4).asDiagonal());
    auto with_vote = tree;
    with_vote.push_back(vote);
    for (const auto& [from, to] : {std::pair<std::size_t, std::size_t>{2, 8}, {8, 3}, {4, 9}}) {
      const auto p = gasp::predictThroughRelocalisation(tree, 12, vote, from, to);
      const auto q = gasp::composeAlongTree(with_vote, 12, from, to);
      ASSERT_TRUE(p && q) << h.from << " -> " << h.to << ", " << from << " -> " << to;
      EXPECT_TRUE(p->T_a_b.isApprox(q->T_a_b, 1e-12));
      EXPECT_TRUE(p->covariance.isApprox(q->covariance, 1e-9))
          << h.from << " -> " << h.to << ", " << from << " -> " << to << "\n"
          << p->covariance << "\n\n"
          << q->covariance;
    }
  }
}

TEST(RelocalisationVotes, TwoAgreeingVotesJoinAndAWrongOneIsLeftOut) {
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);  // 0, 5, 10
  gasp::RelocalisationVotes votes(gasp::LoopClosureParams{});  // 2 agreeing votes
  auto d = votes.offer(constraint(1, 6), 100, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_TRUE(std::isnan(d.chi2));
  EXPECT_NE(d.reason.find("waits for 1 more"), std::string::npos) << d.reason;
  // 30 cm off: disagrees, waits too.
  d = votes.offer(constraint(3, 8, shifted(0.3)), 101, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_GT(d.chi2, 22.46);
  EXPECT_NE(d.reason.find("disagrees"), std::string::npos) << d.reason;
  // A vote between other pieces does not count for these.
  d = votes.offer(constraint(11, 2), 102, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_TRUE(std::isnan(d.chi2));
  EXPECT_EQ(votes.waiting().size(), 3u);
  // 2 cm off (within the uncertainties of the two paths): agrees with the first, joins.
  d = votes.offer(constraint(2, 9, shifted(0.02)), 103, tree, 12, roots);
  ASSERT_TRUE(d.join) << d.reason;
  EXPECT_LE(d.chi2, 22.46);
  ASSERT_EQ(d.votes.size(), 2u);
  EXPECT_EQ(d.votes[0].attempt, 100u);
  EXPECT_EQ(d.votes[1].attempt, 103u);
  EXPECT_TRUE(d.reason.empty());
  ASSERT_EQ(votes.waiting().size(), 2u);  // the wrong vote and the other pieces' vote
  // Once the pieces are joined, the wrong vote is removed; the third piece's vote still waits.
  auto edges = tree;
  for (const auto& v : d.votes) edges.push_back(v.constraint);
  const auto removed = votes.removeJoined(gasp::pieceRoots(12, edges));
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].attempt, 101u);
  ASSERT_EQ(votes.waiting().size(), 1u);
  EXPECT_EQ(votes.waiting()[0].attempt, 102u);
}

TEST(RelocalisationVotes, VotesTheOtherWayRoundAndTheNumberNeeded) {
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);
  gasp::LoopClosureParams p;
  gasp::RelocalisationVotes two(p);
  EXPECT_FALSE(two.offer(constraint(1, 6), 0, tree, 12, roots).join);
  // From the later piece to the earlier one: the same two pieces.
  const auto d = two.offer(constraint(8, 0), 1, tree, 12, roots);
  EXPECT_TRUE(d.join) << d.reason;
  // One vote joins at once.
  p.relocalisation_agreeing = 1;
  gasp::RelocalisationVotes one(p);
  EXPECT_TRUE(one.offer(constraint(3, 8, shifted(0.3)), 0, tree, 12, roots).join);
  EXPECT_TRUE(one.waiting().empty());
  // Three: two waiting ones must agree with the third.
  p.relocalisation_agreeing = 3;
  gasp::RelocalisationVotes three(p);
  EXPECT_FALSE(three.offer(constraint(1, 6), 0, tree, 12, roots).join);
  EXPECT_FALSE(three.offer(constraint(2, 7), 1, tree, 12, roots).join);
  EXPECT_EQ(three.offer(constraint(4, 9), 2, tree, 12, roots).votes.size(), 3u);
  EXPECT_THROW(three.offer(constraint(4, 30), 3, tree, 12, roots), gasp::Error);
  // A vote whose information is not positive definite is refused, not queued.
  PoseConstraint singular = constraint(3, 8);
  singular.information.setZero();
  const auto refused = three.offer(singular, 4, tree, 12, roots);
  EXPECT_FALSE(refused.join);
  EXPECT_NE(refused.reason.find("not positive definite"), std::string::npos) << refused.reason;
  EXPECT_TRUE(three.waiting().empty());
  p.relocalisation_agreeing = 0;
  EXPECT_THROW(gasp::validate(p), gasp::Error);
  // The search looks at kMaxCandidates waiting votes, so more than kMaxCandidates + 1 needed
  // could never join: refused rather than waiting for ever.
  static_assert(gasp::RelocalisationVotes::kMaxCandidates + 1 == gasp::LoopClosureParams::kMaxRelocalisationAgreeing);
  p.relocalisation_agreeing = gasp::LoopClosureParams::kMaxRelocalisationAgreeing;
  EXPECT_NO_THROW(gasp::validate(p));
  p.relocalisation_agreeing = gasp::LoopClosureParams::kMaxRelocalisationAgreeing + 1;
  EXPECT_THROW(gasp::validate(p), gasp::Error);
}

TEST(RelocalisationVotes, TheVotesThatJoinAgreeAmongThemselves) {
  // Three needed. Two waiting votes 6 cm off either way each agree with an exact third, but not
  // with each other: no join (the third is not the proof that both are right).
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);
  gasp::LoopClosureParams p;
  p.relocalisation_agreeing = 3;
  gasp::RelocalisationVotes votes(p);
  EXPECT_FALSE(votes.offer(constraint(1, 6, shifted(-0.06)), 0, tree, 12, roots).join);
  auto d = votes.offer(constraint(2, 7, shifted(0.06)), 1, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_GT(d.chi2, 22.46) << "the two waiting votes must disagree, or the test shows nothing";
  d = votes.offer(constraint(3, 8), 2, tree, 12, roots);
  EXPECT_FALSE(d.join) << "joined by " << d.votes.size() << " votes";
  EXPECT_LE(d.chi2, 22.46) << "the exact vote must agree with each, or the test shows nothing";
  EXPECT_NE(d.reason.find("disagree among themselves"), std::string::npos) << d.reason;
  // A fourth, exact as well: it, the third and the better of the first two (or either) agree.
  d = votes.offer(constraint(4, 9), 3, tree, 12, roots);
  ASSERT_TRUE(d.join) << d.reason;
  ASSERT_EQ(d.votes.size(), 3u);
  EXPECT_EQ(d.votes.back().attempt, 3u);
  EXPECT_EQ(votes.waiting().size(), 1u);  // one of the two 6-cm votes is left out
}

TEST(RelocalisationVotes, TheLargestAgreeingSetJoinsNotTheFirstFound) {
  // Three needed. A waiting vote 5 cm off one way agrees best with a new exact vote; two
  // waiting votes 6 cm off the other way (the same registration twice) agree with it too and
  // with each other, but not with the first. Taking the best-agreeing vote first would leave one vote: the two join instead.
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);
  gasp::LoopClosureParams p;
  p.relocalisation_agreeing = 3;
  gasp::RelocalisationVotes votes(p);
  {  // what makes a best-first choice fail: the 5 cm vote agrees with the exact one, and best
    gasp::RelocalisationVotes alone(p), other(p);
    alone.offer(constraint(1, 6, shifted(-0.05)), 0, tree, 12, roots);
    other.offer(constraint(2, 7, shifted(0.06)), 0, tree, 12, roots);
    const double chi2_5cm = alone.offer(constraint(4, 9), 1, tree, 12, roots).chi2;
    const double chi2_6cm = other.offer(constraint(4, 9), 1, tree, 12, roots).chi2;
    EXPECT_LE(chi2_5cm, 22.46) << "the test shows nothing";
    EXPECT_LE(chi2_6cm, 22.46) << "the test shows nothing";
    EXPECT_LT(chi2_5cm, chi2_6cm) << "the test shows nothing";
  }
  EXPECT_FALSE(votes.offer(constraint(1, 6, shifted(-0.05)), 0, tree, 12, roots).join);
  auto d = votes.offer(constraint(2, 7, shifted(0.06)), 1, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_GT(d.chi2, 22.46) << "the first two must disagree, or the test shows nothing";
  d = votes.offer(constraint(2, 7, shifted(0.06)), 2, tree, 12, roots);
  EXPECT_FALSE(d.join) << "the third agrees with the second only: two votes, three needed";
  EXPECT_LE(d.chi2, 22.46) << "the second and third must agree, or the test shows nothing";
  d = votes.offer(constraint(4, 9), 3, tree, 12, roots);
  ASSERT_TRUE(d.join) << d.reason;
  ASSERT_EQ(d.votes.size(), 3u);
  EXPECT_EQ(d.votes[0].attempt, 1u);
  EXPECT_EQ(d.votes[1].attempt, 2u);
  EXPECT_EQ(d.votes[2].attempt, 3u);
  ASSERT_EQ(votes.waiting().size(), 1u);
  EXPECT_EQ(votes.waiting()[0].attempt, 0u);
}

TEST(RelocalisationVotes, ManyWaitingVotesAreSearchedInBoundedTime) {
  // 40 waiting votes between the same two pieces, alternately 5 cm off either way: two groups
  // that agree within themselves, not with each other, so the agreement graph is far from
  // complete. 25 are needed (the most allowed): the new exact vote agrees with every one, but of
  // the best kMaxCandidates = 24 searched no 24 agree among themselves, so it waits.
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);
  gasp::LoopClosureParams p;
  p.relocalisation_agreeing = gasp::LoopClosureParams::kMaxRelocalisationAgreeing;
  gasp::RelocalisationVotes votes(p);
  for (std::size_t k = 0; k < 40; ++k) {
    const std::size_t from = k % 5, to = 5 + (k / 5) % 5;
    EXPECT_FALSE(votes.offer(constraint(from, to, shifted(k % 2 ? 0.05 : -0.05)), k, tree, 12, roots).join);
  }
  const auto d = votes.offer(constraint(4, 9), 40, tree, 12, roots);
  EXPECT_FALSE(d.join);
  EXPECT_LE(d.chi2, 22.46) << "the new vote must agree with the waiting ones, or the test shows nothing";
  EXPECT_NE(d.reason.find("disagree among themselves"), std::string::npos) << d.reason;
  EXPECT_EQ(votes.waiting().size(), 41u);
}

TEST(RelocalisationVotes, TheMostAllowedJoinWhenAllAgree) {
  // 25 needed, every vote exact: the 25th joins with exactly the 24 waiting ones (the search's
  // whole candidate list).
  const auto tree = odometry();
  const auto roots = gasp::pieceRoots(12, tree);
  gasp::LoopClosureParams p;
  p.relocalisation_agreeing = gasp::LoopClosureParams::kMaxRelocalisationAgreeing;
  gasp::RelocalisationVotes votes(p);
  for (std::size_t k = 0; k + 1 < p.relocalisation_agreeing; ++k) {
    const auto d = votes.offer(constraint(k % 5, 5 + (k / 5) % 5), k, tree, 12, roots);
    EXPECT_FALSE(d.join) << "vote " << k;
  }
  const auto d = votes.offer(constraint(4, 9), 99, tree, 12, roots);
  ASSERT_TRUE(d.join) << d.reason;
  EXPECT_EQ(d.votes.size(), p.relocalisation_agreeing);
  EXPECT_EQ(d.votes.back().attempt, 99u);
  EXPECT_TRUE(votes.waiting().empty());
}
