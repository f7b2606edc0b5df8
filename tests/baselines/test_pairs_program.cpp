// gasp-pairs with the baselines and gasp-pairs-plot, end to end on fr1_desk9 (skipped without the
// real data): rows per method, the colour methods' "n/a (no rgb)" on a copy without rgb, the
// pictures, the figure.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::ProgramRun;

ProgramRun run(const std::string& program, const std::string& args) {
  return gasp::test::runProgram(program, args);
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(f, l);) out.push_back(l);
  return out;
}

/// The fields of one CSV line (a quoted field may hold commas).
std::vector<std::string> splitCsv(const std::string& s) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : s) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

/// Index of the named column in a CSV header (a failure, and the header's size, when absent).
std::size_t columnIndex(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << name;
  return static_cast<std::size_t>(it - header.begin());
}

/// A pairs CSV, split: the header and the rows.
struct PairsCsv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const { return columnIndex(header, name); }
};

/// gasp-pairs `--method gasp` on DIR's pairs 0 -> 4 and 4 -> 8 with `flags` and a pairs CSV at
/// `path`. A failure (and no rows) unless it exits 0 and every row has the header's width and an
/// estimate.
PairsCsv gaspPairsCsv(const std::string& dir, const std::string& flags, const std::string& path) {
  PairsCsv out;
  const auto r = run("gasp-pairs", "--tum " + dir + " --skips 4 --starts-every 4 --method gasp " + flags + " --pairs-csv " + path);
  if (r.exit_code != 0) {
    ADD_FAILURE() << "gasp-pairs exited with " << r.exit_code << ": " << r.output;
    return out;
  }
  const auto text = lines(path);
  if (text.empty()) {
    ADD_FAILURE() << "empty " << path;
    return out;
  }
  out.header = splitCsv(text[0]);
  for (std::size_t k = 1; k < text.size(); ++k) {
    auto c = splitCsv(text[k]);
    EXPECT_EQ(c.size(), out.header.size()) << text[k];
    if (c.size() != out.header.size()) return PairsCsv{};
    EXPECT_EQ(c[out.column("estimated")], "1") << text[k];
    out.rows.push_back(std::move(c));
  }
  return out;
}

}  // namespace

TEST(PairsProgram, BaselinesBesideGaspOnTheSamePairs) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string tmp = gasp::test::scratchDir();
  const std::string csv = tmp + "/t.csv", pairs = tmp + "/p.csv";
  const auto r = run("gasp-pairs", "--tum " + dir + " --skips 1,4 --starts-every 4 --method gasp,fpfh,sift --csv " +
                                       csv + " --pairs-csv " + pairs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("median_ms_per_stage fpfh: check"), std::string::npos) << r.output;
  const auto rows = lines(csv);
  ASSERT_EQ(rows.size(), 1u + 2 * 3) << r.output;  // header + 2 skips x 3 methods
  // The easy pairs of fr1_desk9 (0->1, 4->5, 0->4, 4->8): every method estimates every pair.
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_NE(rows[k].find(",2,0,"), std::string::npos) << rows[k];
  EXPECT_EQ(lines(pairs).size(), 1u + 4 * 3);

  // The figure from the table.
  const std::string png = tmp + "/fig.png";
  const auto p = run("gasp-pairs-plot", "--csv " + csv + " --out " + png + " --caption test");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  EXPECT_FALSE(cv::imread(png).empty());
  EXPECT_EQ(run("gasp-pairs-plot", "--csv " + pairs + " --out " + png).exit_code, 1);  // not a table
}

// gicp: PCL's GICP from the identity, the same visibility check as every method; gasp-gicp: GICP
// from GASP's pose (GASP's pose kept when GICP fails or is declined). On fr1_desk9's pairs 4 frames
// apart GASP's start gives GICP poses within a few cm; the NEES belongs to GASP's own pose only.
TEST(PairsProgram, GicpFromTheIdentityAndFromGaspsPose) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string tmp = gasp::test::scratchDir();
  const std::string pairs = tmp + "/p.csv";
  const auto r = run("gasp-pairs", "--tum " + dir + " --skips 4 --starts-every 4 --method gasp,gasp-gicp,gicp --pairs-csv " + pairs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("median_ms_per_stage gicp: check"), std::string::npos) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("median_ms_per_stage gasp-gicp: association [0-9.]+ gicp\\+check [0-9.]+"))) << r.output;
  const auto text = lines(pairs);
  ASSERT_EQ(text.size(), 1u + 2 * 3) << r.output;  // pairs 0 -> 4, 4 -> 8; three methods each
  const auto header = splitCsv(text[0]);
  const std::size_t method = columnIndex(header, "method"), estimated = columnIndex(header, "estimated"),
                    t_err = columnIndex(header, "t_err_m"), r_err = columnIndex(header, "r_err_deg"),
                    nees = columnIndex(header, "nees"), qw = columnIndex(header, "qw"), ms = columnIndex(header, "ms");
  std::map<std::string, std::vector<std::vector<std::string>>> by_method;
  for (std::size_t k = 1; k < text.size(); ++k) {
    auto c = splitCsv(text[k]);
    ASSERT_EQ(c.size(), header.size()) << text[k];
    by_method[c[method]].push_back(std::move(c));
  }
  ASSERT_EQ(by_method["gasp"].size(), 2u);
  ASSERT_EQ(by_method["gasp-gicp"].size(), 2u);
  ASSERT_EQ(by_method["gicp"].size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& g = by_method["gasp"][k];
    const auto& gi = by_method["gasp-gicp"][k];
    ASSERT_EQ(gi[estimated], "1") << text[1 + 3 * k];
    EXPECT_LT(std::stod(gi[t_err]), 0.03);
    EXPECT_LT(std::stod(gi[r_err]), 2.0);
    EXPECT_FALSE(g[nees].empty());
    EXPECT_TRUE(gi[nees].empty());  // no information for GICP's pose
    EXPECT_GT(std::stod(gi[ms]), std::stod(g[ms]));  // GASP's time plus GICP's
    // GICP moved GASP's pose (it converged and passed the check) or the reason says it was kept.
    EXPECT_TRUE(gi[qw] != g[qw] || gi.back().find("GASP's pose kept") != std::string::npos) << gi.back();
    // GICP from the identity: a pose that passed the visibility check, or the reason it has none.
    const auto& ic = by_method["gicp"][k];
    if (ic[estimated] == "1") {
      EXPECT_FALSE(ic[qw].empty());
    } else {
      EXPECT_FALSE(ic.back().empty());
    }
  }
}

TEST(PairsProgram, ColourMethodsAreNotApplicableWithoutRgb) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string tmp = gasp::test::scratchDir();
  namespace fs = std::filesystem;
  const std::string copy = tmp + "/fr1_desk9_depth_only";
  fs::create_directories(copy);
  fs::copy(dir + "/depth", copy + "/depth", fs::copy_options::recursive);
  fs::copy_file(dir + "/depth.txt", copy + "/depth.txt");
  fs::copy_file(dir + "/groundtruth.txt", copy + "/groundtruth.txt");
  const auto r = run("gasp-pairs", "--tum " + copy + " --intrinsics fr1 --skips 2 --starts-every 3 --method shot,sift,cshot");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("sift           n/a (no rgb: 3 pairs left out)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cshot          n/a (no rgb: 3 pairs left out)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2      shot                3"), std::string::npos) << r.output;
  // Only colour methods and no rgb: nothing to score.
  EXPECT_EQ(run("gasp-pairs", "--tum " + copy + " --intrinsics fr1 --skips 2 --method sift").exit_code, 4);
}

TEST(PairsProgram, OnePicturePerMethod) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string prefix = gasp::test::scratchDir() + "/pic_";
  const auto r = run("gasp-pairs", "--tum " + dir + " --picture 0,4 --pictures-only --method gasp,shot,dsift --picture-prefix " + prefix);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string m : {"gasp", "shot", "dsift"}) {
    const cv::Mat pic = cv::imread(prefix + m + ".png");
    ASSERT_FALSE(pic.empty()) << m;
    EXPECT_EQ(pic.cols, 2 * 640) << m;
    EXPECT_NE(r.output.find("picture " + m + ": "), std::string::npos) << r.output;
  }
  EXPECT_NE(r.output.find("pose error"), std::string::npos) << r.output;
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --pictures-only").exit_code, 2);
}

TEST(PairsProgram, PolishReferenceFillsTheGicpColumns) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string pairs = gasp::test::scratchDir() + "/polish.csv";
  const PairsCsv csv = gaspPairsCsv(dir, "--polish-reference", pairs);
  ASSERT_EQ(csv.rows.size(), 2u);  // 0 -> 4, 4 -> 8
  auto column = [&](const std::string& name) { return csv.column(name); };
  for (const auto& c : csv.rows) {
    const std::string row = c[column("from")] + " -> " + c[column("to")];
    for (const std::string name : {"ref_icp_t_m", "ref_icp_r_deg", "est_vs_ref_icp_t_m", "est_vs_ref_icp_r_deg",
                                   "est_icp_t_m", "est_icp_r_deg", "icp_est_vs_ref_icp_t_m", "icp_est_vs_ref_icp_r_deg"}) {
      const std::string& v = c[column(name)];
      ASSERT_FALSE(v.empty()) << name << ": " << row;
      EXPECT_TRUE(std::isfinite(std::stod(v)) && std::stod(v) >= 0.0) << name << ": " << v;
    }
    // Consecutive-ish fr1_desk frames: GICP from the estimate and from the reference end close.
    EXPECT_LT(std::stod(c[column("icp_est_vs_ref_icp_r_deg")]), 1.0) << row;
    EXPECT_LT(std::stod(c[column("icp_est_vs_ref_icp_t_m")]), 0.03) << row;
  }
  // Without the flag the columns are there and empty.
  const auto plain = run("gasp-pairs", "--tum " + dir + " --skips 4 --starts-every 4 --method gasp --max-pairs 1 --pairs-csv " + pairs);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const auto rows2 = lines(pairs);
  ASSERT_EQ(rows2.size(), 2u);
  const auto c = splitCsv(rows2[1]);
  EXPECT_TRUE(c[column("ref_icp_r_deg")].empty()) << rows2[1];
  // The flag without a pairs file has nowhere to write: a usage error that says so.
  const auto alone = run("gasp-pairs", "--tum " + dir + " --skips 4 --method gasp --polish-reference");
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("--pairs-csv"), std::string::npos) << alone.output;
}

TEST(PairsProgram, RgbRotationCheckFillsItsColumns) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string pairs = gasp::test::scratchDir() + "/rgb_check.csv";
  const PairsCsv csv = gaspPairsCsv(dir, "--rgb-rotation-check", pairs);
  ASSERT_EQ(csv.rows.size(), 2u);  // 0 -> 4, 4 -> 8
  auto column = [&](const std::string& name) { return csv.column(name); };
  for (const auto& c : csv.rows) {
    const std::string row = c[column("from")] + " -> " + c[column("to")];
    // fr1_desk is textured (but blurred): over 100 epipolar inliers here, and the images' rotation within a few
    // degrees of the reference's and of the estimate's (the three disagree by about 1 deg on fr1,
    // docs/pipeline.md "A depth-free check").
    EXPECT_GE(std::stod(c[column("rgb_inliers")]), 50.0) << row;  // min_inliers
    EXPECT_GT(std::stod(c[column("rgb_parallax_px")]), 2.0) << row;
    for (const std::string name : {"rgb_r_vs_ref_deg", "rgb_r_vs_est_deg"}) {
      const std::string& v = c[column(name)];
      ASSERT_FALSE(v.empty()) << name << ": " << row;
      EXPECT_LT(std::stod(v), 3.0) << name << ": " << row;
    }
    EXPECT_TRUE(c[column("rgb_r_vs_ref_icp_deg")].empty()) << "no --polish-reference: " << row;
  }
  const auto alone = run("gasp-pairs", "--tum " + dir + " --skips 4 --method gasp --rgb-rotation-check");
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("--pairs-csv"), std::string::npos) << alone.output;
}

TEST(PairsProgram, RgbIntrinsicsKeepTheImagesRotationWhenTheDepthIsRecalibrated) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  // A depth calibration in --intrinsics (focal lengths x 1.05, lens coefficients rescaled so that
  // the undistortion maps every pixel as before) must not change the colour camera the rgb check
  // uses when --rgb-intrinsics names it.
  const std::string scratch = gasp::test::scratchDir();  // emptied on every call: once per test
  const std::string k_file = scratch + "/depth_k1.05.txt";
  {
    std::ofstream f(k_file);
    const double k = 1.05;
    f << "width: 640\nheight: 480\nfx: " << 517.3 * k << "\nfy: " << 516.5 * k << "\ncx: 318.6\ncy: 255.3\n"
      << "distortion: " << 0.2624 * k * k << ' ' << -0.9531 * std::pow(k, 4) << ' ' << -0.0054 * k << ' ' << 0.0026 * k
      << ' ' << 1.1633 * std::pow(k, 6) << "\n";
  }
  const std::string plain = scratch + "/rgb_plain.csv";
  const std::string recal = scratch + "/rgb_recal.csv";
  const std::string common = "--tum " + dir + " --skips 4 --starts-every 4 --method gasp --rgb-rotation-check ";
  ASSERT_EQ(run("gasp-pairs", common + "--pairs-csv " + plain).exit_code, 0);
  const auto r = run("gasp-pairs", common + "--intrinsics " + k_file + " --depth-scale 4761.9 --rgb-intrinsics fr1 --pairs-csv " + recal);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto a = lines(plain), b = lines(recal);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  const auto header = splitCsv(a[0]);
  const std::size_t col = columnIndex(header, "rgb_r_vs_ref_deg");
  ASSERT_LT(col, header.size());
  for (std::size_t i = 1; i < 3; ++i) {
    const auto ca = splitCsv(a[i]), cb = splitCsv(b[i]);
    ASSERT_FALSE(ca[col].empty()) << a[i];
    ASSERT_FALSE(cb[col].empty()) << b[i];
    EXPECT_NEAR(std::stod(ca[col]), std::stod(cb[col]), 0.05) << a[i] << "\n" << b[i];
  }
  // A colour camera of another size than the images: an error that names the option.
  const std::string small = scratch + "/small.txt";
  std::ofstream(small) << "width: 320\nheight: 240\nfx: 260\nfy: 260\ncx: 160\ncy: 120\n";
  const auto bad = run("gasp-pairs", common + "--rgb-intrinsics " + small + " --pairs-csv " + recal);
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("--rgb-intrinsics"), std::string::npos) << bad.output;
}
