// Development tool (not a test): times associateFeatureSets() against the first implementation
// (reference_association.h) on the same segmented TUM pair, checks the precision / density of
// both, and with --analyse prints statistics used to tune the search (rank of the exact best
// partner in the KD-tree order, band widths, match rates).
//   assoc_bench --tum DIR --from I --to J [--reps 5] [--threads 2] [--analyse] [--micro] [--k 30]
//               [--candidates 20] [--key mean|quantiles] [--lambda 0.5] [--no-mutual] [--no-reference]
//               [--ref-candidates 75]
// Times are the minimum over the repetitions (wall and process CPU); "identical to reference"
// compares the associations exactly (meaningful with --key mean and the same C).
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <numeric>
#include <string>
#include <vector>

#include "gasp/core/stopwatch.h"
#include "gasp/association/association_quality.h"
#include "gasp/association/banded_distance.h"
#include "gasp/association/view_association.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "reference_association.h"

namespace {

using gasp::msSince;

/// CPU time of the process [ms] (all threads): less sensitive to other load than wall time.
double cpuMs() { return 1000.0 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// Minimum over the repetitions: the least disturbed by other load on the machine.
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[0];
}

bool same(const std::vector<gasp::PatchAssociation>& x, const std::vector<gasp::PatchAssociation>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].a != y[i].a || x[i].b != y[i].b || x[i].distance != y[i].distance) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir;
  std::size_t from = 0, to = 0;
  int reps = 5, threads = 2, ref_candidates = 75;
  bool analyse = false, run_reference = true, micro = false, rank_mode = false;
  gasp::AssociationParams p;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) std::exit(2);
      return argv[++i];
    };
    if (a == "--tum") dir = next();
    else if (a == "--from") from = std::strtoul(next(), nullptr, 10);
    else if (a == "--to") to = std::strtoul(next(), nullptr, 10);
    else if (a == "--reps") reps = std::atoi(next());
    else if (a == "--threads") threads = std::atoi(next());
    else if (a == "--k") p.feature_sets.neighbourhood.k = std::atoi(next());
    else if (a == "--candidates") p.candidates = std::atoi(next());
    else if (a == "--lambda") p.lambda = std::atof(next());
    else if (a == "--no-mutual") p.mutual_check = false;
    else if (a == "--key") p.candidate_key = std::string(next()) == "mean" ? gasp::CandidateKey::kMean : gasp::CandidateKey::kQuantiles;
    else if (a == "--analyse") analyse = true;
    else if (a == "--micro") micro = true;
    else if (a == "--ranks") rank_mode = true;
    else if (a == "--no-reference") run_reference = false;
    else if (a == "--ref-candidates") ref_candidates = std::atoi(next());
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const auto ds = gasp::TumDataset::open(dir);
  const cv::Mat depth_a = ds.loadDepth(from), depth_b = ds.loadDepth(to);
  const auto seg_a = gasp::segmentDepthSuperpixels(depth_a, ds.intrinsics());
  const auto seg_b = gasp::segmentDepthSuperpixels(depth_b, ds.intrinsics());
  const auto ga = gasp::toPatchGeometry(seg_a.patches), gb = gasp::toPatchGeometry(seg_b.patches);
  const auto qa = gasp::computeFeatureSets(ga, p.feature_sets);
  const auto qb = gasp::computeFeatureSets(gb, p.feature_sets);
  const auto T_b_a = gasp::relativePose(*ds.frame(to).T_world_camera, *ds.frame(from).T_world_camera);
  std::printf("patches %zu -> %zu, k %d, C %d (%s), lambda %.2f, mutual %d, threads %d\n", ga.size(), gb.size(),
              p.feature_sets.neighbourhood.k, p.candidates, p.candidate_key == gasp::CandidateKey::kMean ? "mean" : "quantiles",
              p.lambda, int(p.mutual_check), threads);

  const auto report = [&](const char* name, const std::vector<gasp::PatchAssociation>& s, double ms, double cpu) {
    const auto q = gasp::evaluateAssociations(s, seg_a, seg_b, depth_b, ds.intrinsics(), T_b_a);
    std::printf("%-10s %8.2f ms wall %8.2f ms cpu  associations %4d  correct %4d  precision %.3f  density %.3f\n",
                name, ms, cpu, q.associations, q.correct, q.precision(), q.density());
  };

  if (rank_mode) {
    // How discriminative are the feature sets? For every patch of A with a true partner in B
    // (isSameSurface under the true pose), the rank of its best true partner among all of B by
    // exact D_hat (ties counted against it), over every patch of B.
    const gasp::FeatureMatch match{p.match};
    gasp::EditDistanceWorkspace ews;
    std::array<int, 6> hist{};  // rank 1, 2-3, 4-10, 11-20, 21-75, > 75
    int with_partner = 0;
    for (std::size_t i = 0; i < qa.size(); ++i) {
      if (qa[i].empty()) continue;
      std::vector<double> hat(qb.size(), 2.0);
      double best_true = 3.0;
      for (std::size_t j = 0; j < qb.size(); ++j) {
        if (qb[j].empty()) continue;
        hat[j] = gasp::osaDistance(qa[i], qb[j], match, p.costs, gasp::kExceedsBound, ews) /
                 static_cast<double>(qa[i].size() + qb[j].size());
        if (gasp::isSameSurface(seg_a.patches[i], seg_b.patches[j], T_b_a)) best_true = std::min(best_true, hat[j]);
      }
      if (best_true > 2.5) continue;
      ++with_partner;
      int rank = 1;
      for (std::size_t j = 0; j < qb.size(); ++j)
        if (hat[j] < best_true) ++rank;
      hist[rank == 1 ? 0 : rank <= 3 ? 1 : rank <= 10 ? 2 : rank <= 20 ? 3 : rank <= 75 ? 4 : 5]++;
    }
    std::printf("ranks of the best true partner (%d patches of A with one): 1: %d  2-3: %d  4-10: %d  11-20: %d  21-75: %d  >75: %d\n",
                with_partner, hist[0], hist[1], hist[2], hist[3], hist[4], hist[5]);
    return 0;
  }

  if (micro) {
    // Cost of one comparison: every 7th patch of A against every 5th patch of B.
    std::vector<gasp::PreparedFeatureSet> pa, pb;
    for (const auto& q : qa) pa.push_back(gasp::prepareFeatureSet(q, p.match, p.feature_sets.ordering));
    for (const auto& q : qb) pb.push_back(gasp::prepareFeatureSet(q, p.match, p.feature_sets.ordering));
    gasp::BandedWorkspace bws;
    gasp::EditDistanceWorkspace ews;
    const gasp::FeatureMatch match{p.match};
    for (const double lam : {1.0, 0.5, 0.3}) {
      double sink = 0;
      std::size_t calls = 0;
      const double c0 = cpuMs();
      for (std::size_t i = 0; i < qa.size(); i += 7)
        for (std::size_t j = 0; j < qb.size(); j += 5) {
          if (qa[i].empty() || qb[j].empty()) continue;
          const double bound = lam * static_cast<double>(qa[i].size() + qb[j].size());
          const double d = gasp::featureSetDistance(pa[i], pb[j], p.match, p.costs, bound, bws);
          sink += d == gasp::kExceedsBound ? 0 : d;
          ++calls;
        }
      const double c1 = cpuMs();
      double sink2 = 0;
      for (std::size_t i = 0; i < qa.size(); i += 7)
        for (std::size_t j = 0; j < qb.size(); j += 5) {
          if (qa[i].empty() || qb[j].empty()) continue;
          const double bound = lam * static_cast<double>(qa[i].size() + qb[j].size());
          const double d = gasp::osaDistance(qa[i], qb[j], match, p.costs, bound, ews);
          sink2 += d == gasp::kExceedsBound ? 0 : d;
        }
      const double c2 = cpuMs();
      std::printf("lambda %.1f: %zu calls, banded %.3f us, osaDistance %.3f us per call (sums %.0f %.0f)\n", lam, calls,
                  1000 * (c1 - c0) / calls, 1000 * (c2 - c1) / calls, sink, sink2);
    }
  }

  if (micro) {
    // How tight are 1D matching bounds (per component, greedy maximum matching of sorted values
    // within the tolerance) against the true number of matched elements, on the comparisons the
    // search makes (A -> B, KD-tree order, bound tightened to the best so far)?
    std::vector<std::array<std::vector<double>, 7>> sa(qa.size()), sb(qb.size());
    auto sorted = [&](const std::vector<gasp::Feature>& q, std::array<std::vector<double>, 7>& out) {
      for (int c = 0; c < 7; ++c) {
        for (const auto& f : q) out[c].push_back(f[c]);
        std::sort(out[c].begin(), out[c].end());
      }
    };
    for (std::size_t i = 0; i < qa.size(); ++i) sorted(qa[i], sa[i]);
    for (std::size_t j = 0; j < qb.size(); ++j) sorted(qb[j], sb[j]);
    auto greedy = [](const std::vector<double>& x, const std::vector<double>& y, double tol) {
      std::size_t i = 0, j = 0, mm = 0;
      while (i < x.size() && j < y.size()) {
        if (std::abs(x[i] - y[j]) <= tol) { ++mm; ++i; ++j; }
        else if (x[i] < y[j]) ++i;
        else ++j;
      }
      return mm;
    };
    std::vector<gasp::test::reference::Mean> mb(qb.size());
    gasp::test::reference::MeanCloud cloud;
    std::vector<int> ids;
    for (std::size_t j = 0; j < qb.size(); ++j)
      if (!qb[j].empty()) { cloud.points.push_back(gasp::test::reference::normalisedMean(qb[j], p.match)); ids.push_back(int(j)); }
    gasp::test::reference::MeanTree tree(7, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    const gasp::FeatureMatch match{p.match};
    gasp::EditDistanceWorkspace ews;
    std::size_t comps = 0, cut = 0;
    std::array<std::size_t, 8> cut_by{};
    for (std::size_t i = 0; i < qa.size(); ++i) {
      if (qa[i].empty()) continue;
      const auto q = gasp::test::reference::normalisedMean(qa[i], p.match);
      std::vector<std::uint32_t> idx(75); std::vector<double> dd(75);
      const std::size_t found = tree.knnSearch(q.data(), 75, idx.data(), dd.data());
      double best = 2;
      for (std::size_t c = 0; c < found; ++c) {
        const int j = ids[idx[c]];
        const double denom = double(qa[i].size() + qb[j].size());
        const double bound = std::min(p.lambda, best) * denom;
        const double d = gasp::osaDistance(qa[i], qb[j], match, p.costs, bound, ews);
        ++comps;
        const double needed_pairs = (denom - bound) / 2.0;  // default costs: D = n + m - 2 L
        if (d == gasp::kExceedsBound) {
          ++cut;
          std::size_t mn = 1000;
          for (int cc = 0; cc < 7; ++cc) {
            const auto mm = greedy(sa[i][cc], sb[j][cc], cc < 4 ? p.match.r_dev_m : p.match.theta_dev_rad);
            if (double(mm) < needed_pairs) ++cut_by[cc];
            mn = std::min(mn, mm);
          }
          if (double(mn) < needed_pairs) ++cut_by[7];
        } else if (d / denom < best) best = d / denom;
      }
    }
    std::printf("search comparisons %zu, cut %zu; cut by 1D bound of component 0..6:", comps, cut);
    for (int c = 0; c < 7; ++c) std::printf(" %zu", cut_by[c]);
    std::printf("; any %zu\n", cut_by[7]);
  }

  // The first implementation always searches a KD-tree over the means; with its own C (default
  // 75, the former default).
  gasp::AssociationParams ref_params = p;
  ref_params.candidates = ref_candidates;
  std::vector<gasp::PatchAssociation> ref;
  if (run_reference) {
    std::vector<double> t, c;
    for (int r = 0; r < reps; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpuMs();
      ref = gasp::test::reference::associate(qa, qb, ref_params);
      t.push_back(msSince(t0));
      c.push_back(cpuMs() - c0);
    }
    std::printf("reference: first implementation, KD-tree over means, C %d\n", ref_candidates);
    report("reference", ref, median(t), median(c));
  }
  gasp::AssociationResult res;
  {
    std::vector<double> t, tm, c, tt;
    for (int r = 0; r < reps; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpuMs();
      res = gasp::associateFeatureSets(qa, qb, p);
      t.push_back(msSince(t0));
      c.push_back(cpuMs() - c0);
      tm.push_back(res.stats.matching_ms);
      tt.push_back(res.stats.tree_ms);
    }
    report("current", res.associations, median(t), median(c));
    const auto& s = res.stats;
    std::printf("           min matching %.2f ms, tree %.2f ms; comparisons %zu, cut early %zu, gated %zu, not mutual %zu\n",
                median(tm), median(tt), s.comparisons, s.cut_early, s.gated_out, s.not_mutual);
    if (run_reference) std::printf("identical to reference: %s\n", same(ref, res.associations) ? "yes" : "NO");
  }

  if (analyse) {
    // Exact best partner of every a over all of B (A -> B), and its rank in the plain-mean order.
    const std::size_t na = qa.size(), nb = qb.size();
    std::vector<gasp::test::reference::Mean> mb(nb);
    for (std::size_t j = 0; j < nb; ++j)
      if (!qb[j].empty()) mb[j] = gasp::test::reference::normalisedMean(qb[j], p.match);
    // Candidate descriptors: per-component quantiles / mean / std, normalised by the tolerance.
    using Desc = std::vector<double>;
    auto quantiles = [&](const std::vector<gasp::Feature>& q, const std::vector<double>& qs, int comps_mask, bool add_mean) {
      Desc d;
      for (int c = 0; c < 7; ++c) {
        if (!(comps_mask >> c & 1)) continue;
        const double tol = c < 4 ? p.match.r_dev_m : p.match.theta_dev_rad;
        std::vector<double> v;
        for (const auto& f : q) v.push_back(f[c] / tol);
        std::sort(v.begin(), v.end());
        for (double x : qs) {
          const double pos = x * static_cast<double>(v.size() - 1);
          const std::size_t k0 = static_cast<std::size_t>(pos);
          const double t = pos - static_cast<double>(k0);
          d.push_back(v.empty() ? 0.0 : v[k0] * (1 - t) + v[std::min(k0 + 1, v.size() - 1)] * t);
        }
        if (add_mean) {
          double mu = 0;
          for (double x : v) mu += x;
          d.push_back(v.empty() ? 0 : mu / static_cast<double>(v.size()));
        }
      }
      return d;
    };
    auto meanStd = [&](const std::vector<gasp::Feature>& q) {
      Desc d;
      for (int c = 0; c < 7; ++c) {
        const double tol = c < 4 ? p.match.r_dev_m : p.match.theta_dev_rad;
        double s1 = 0, s2 = 0;
        for (const auto& f : q) { s1 += f[c] / tol; s2 += (f[c] / tol) * (f[c] / tol); }
        const double nn = std::max<double>(1, static_cast<double>(q.size()));
        d.push_back(s1 / nn);
        d.push_back(std::sqrt(std::max(0.0, s2 / nn - (s1 / nn) * (s1 / nn))));
      }
      return d;
    };
    std::vector<std::pair<std::vector<Desc>, int>> descs;
    std::vector<std::vector<Desc>> descB;
    std::vector<const char*> names;
    auto addDesc = [&](const char* name, int mode, auto fn) {
      std::vector<Desc> da(na), db(nb);
      for (std::size_t i = 0; i < na; ++i) da[i] = fn(qa[i]);
      for (std::size_t j = 0; j < nb; ++j) db[j] = fn(qb[j]);
      descs.emplace_back(std::move(da), mode);
      descB.push_back(std::move(db));
      names.push_back(name);
    };
    // Ranks (k + 0.5) / Q, Q = 5 and 9 (9 = the production CandidateKey::kQuantiles).
    std::vector<double> q5, q9;
    for (int k = 0; k < 5; ++k) q5.push_back((k + 0.5) / 5);
    for (int k = 0; k < 9; ++k) q9.push_back((k + 0.5) / 9);
    addDesc("mean+std L2", 0, meanStd);
    addDesc("quant5 L1", 1, [&](const auto& q) { return quantiles(q, q5, 127, false); });
    addDesc("quant9 L1", 1, [&](const auto& q) { return quantiles(q, q9, 127, false); });
    addDesc("quant9 L2", 0, [&](const auto& q) { return quantiles(q, q9, 127, false); });
    std::vector<std::vector<int>> dranks(descs.size());
    std::vector<int> ranks;
    int best_correct = 0, best_total = 0;
    double cells = 0, band_cells = 0, match_cells = 0;
    std::size_t pairs = 0;
    gasp::EditDistanceWorkspace ws;
    const gasp::FeatureMatch match{p.match};
    for (std::size_t i = 0; i < na; ++i) {
      if (qa[i].empty()) continue;
      const auto ma = gasp::test::reference::normalisedMean(qa[i], p.match);
      double best = 2.0;
      int best_j = -1;
      std::vector<std::pair<double, int>> order;
      for (std::size_t j = 0; j < nb; ++j) {
        if (qb[j].empty()) continue;
        double d2 = 0;
        for (int c = 0; c < 7; ++c) d2 += (ma[c] - mb[j][c]) * (ma[c] - mb[j][c]);
        order.emplace_back(d2, static_cast<int>(j));
        const double denom = static_cast<double>(qa[i].size() + qb[j].size());
        const double d = gasp::osaDistance(qa[i], qb[j], match, p.costs, std::min(p.lambda, best) * denom, ws);
        if (d == gasp::kExceedsBound) continue;
        if (d / denom < best) {
          best = d / denom;
          best_j = static_cast<int>(j);
        }
        if ((i * 7 + j) % 13 == 0) {  // sample of pairs for band statistics
          ++pairs;
        }
      }
      // band statistics on a sample of pairs
      for (std::size_t j = i % 17; j < nb; j += 17) {
        for (const auto& x : qa[i])
          for (const auto& y : qb[j]) {
            cells += 1;
            band_cells += std::abs(x[0] - y[0]) <= p.match.r_dev_m;
            match_cells += match(x, y);
          }
      }
      if (best_j < 0) continue;
      std::sort(order.begin(), order.end());
      int rank = 0;
      while (order[static_cast<std::size_t>(rank)].second != best_j) ++rank;
      ranks.push_back(rank);
      for (std::size_t dsc = 0; dsc < descs.size(); ++dsc) {
        const auto& da = descs[dsc].first[i];
        const auto& mode = descs[dsc].second;
        std::vector<std::pair<double, int>> ord;
        for (std::size_t j = 0; j < nb; ++j) {
          if (qb[j].empty()) continue;
          const auto& db = descs[dsc].first.size() ? descB[dsc][j] : da;
          double d = 0;
          for (std::size_t c = 0; c < da.size(); ++c) {
            const double x = std::abs(da[c] - db[c]);
            d += mode == 0 ? x * x : (mode == 1 ? x : std::min(x, 1.0));
          }
          ord.emplace_back(d, static_cast<int>(j));
        }
        std::sort(ord.begin(), ord.end());
        int rk = 0;
        while (ord[static_cast<std::size_t>(rk)].second != best_j) ++rk;
        dranks[dsc].push_back(rk);
      }
      ++best_total;
      best_correct += gasp::isSameSurface(seg_a.patches[i], seg_b.patches[static_cast<std::size_t>(best_j)], T_b_a);
    }
    std::printf("exact best within lambda: %d of A, precision of the exact argmin (A -> B only) %.3f\n", best_total,
                best_total ? double(best_correct) / best_total : 0.0);
    std::printf("  top C:        ");
    for (int c : {5, 10, 15, 20, 25, 30, 40, 50, 75, 100}) std::printf(" %5d", c);
    std::printf("\n  mean (7D L2): ");
    for (int c : {5, 10, 15, 20, 25, 30, 40, 50, 75, 100}) {
      const auto in = std::count_if(ranks.begin(), ranks.end(), [&](int r) { return r < c; });
      std::printf(" %.3f", ranks.empty() ? 0.0 : double(in) / ranks.size());
    }
    for (std::size_t dsc = 0; dsc < descs.size(); ++dsc) {
      std::printf("\n  %-12s: ", names[dsc]);
      for (int c : {5, 10, 15, 20, 25, 30, 40, 50, 75, 100}) {
        const auto in = std::count_if(dranks[dsc].begin(), dranks[dsc].end(), [&](int r) { return r < c; });
        std::printf(" %.3f", dranks[dsc].empty() ? 0.0 : double(in) / dranks[dsc].size());
      }
    }
    std::printf("\n");
    std::printf("cells: |dq0| <= r_dev %.3f, match %.4f (of %.0f sampled)\n", band_cells / cells, match_cells / cells, cells);
  }
  return 0;
}
