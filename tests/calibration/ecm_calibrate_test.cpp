// End to end: the ecm-calibrate tool, its outputs and its exit codes (io/cli_exit.hpp: 0 done,
// 1 no result or an output not written once the run had begun, 2 bad input).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/csv_reader.hpp"
#include "io/material_yaml.hpp"
#include "../run_tool.hpp"

namespace {

namespace fs = std::filesystem;

class EcmCalibrate : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("ecm-calibrate-test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs the tool with `args`; returns its exit status, stdout and stderr in out_/err_.
  int run(const std::string& args) {
    const ecm::test::ToolRun r = ecm::test::runTool(ECM_CALIBRATE, args, dir_);
    out_ = r.out;
    err_ = r.err;
    return r.status;
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  nlohmann::json summary(const fs::path& out) { return nlohmann::json::parse(read(out / "summary.json")); }

  fs::path dir_;
  std::string out_, err_;
};

TEST_F(EcmCalibrate, SolvesEpAndWritesItsOutputs) {
  const fs::path out = dir_ / "solve";
  ASSERT_EQ(run("--E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 --out '" + out.string() + "'"), 0) << err_;
  const nlohmann::json j = summary(out);
  for (const char* key : {"Ep", "n", "GF", "GF_rel_error", "peak_stress", "H_crit", "w_at_50pct_ft", "w_at_10pct_ft",
                          "w_at_1pct_ft"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["Ep"].get<double>(), 8.18, 0.02);
  EXPECT_LE(std::abs(j["GF_rel_error"].get<double>()), 1e-8);
  EXPECT_NEAR(j["H_crit"].get<double>(), 782.2222, 1e-3);
  EXPECT_DOUBLE_EQ(j["peak_stress"].get<double>(), 3.0);
  EXPECT_LT(j["w_at_50pct_ft"].get<double>(), j["w_at_10pct_ft"].get<double>());
  EXPECT_LT(j["w_at_10pct_ft"].get<double>(), j["w_at_1pct_ft"].get<double>());
  EXPECT_FALSE(j.contains("fit_residual"));
  const ecm::io::CsvTable csv = ecm::io::readCsv(out / "softening.csv", 4);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"w", "sigma", "D", "eps_L"}));
  EXPECT_GT(csv.rows.size(), 100u);
  EXPECT_NE(out_.find("softening modulus"), std::string::npos) << out_;
  EXPECT_TRUE(fs::exists(out / "softening.gp"));
  if (std::system("gnuplot --version > /dev/null 2>&1") == 0) {
    EXPECT_TRUE(fs::exists(out / "softening.png"));
  }
}

TEST_F(EcmCalibrate, ForwardGivesTheFractureEnergy) {
  const fs::path out = dir_ / "forward";
  ASSERT_EQ(run("--E 32000 --ft 3.0 --h 0.05 --Ep 8.184 --n 0.128 --out '" + out.string() + "'"), 0) << err_;
  EXPECT_NEAR(summary(out)["GF"].get<double>(), 0.110, 0.001 * 0.110);
}

TEST_F(EcmCalibrate, HordijkFitWritesAMaterialTheOtherToolsRead) {
  const fs::path out = dir_ / "fit", material = dir_ / "fitted.yaml";
  ASSERT_EQ(run("--E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --fit hordijk --name den-fit --out '" + out.string() +
                "' --write-material '" + material.string() + "'"),
            0)
      << err_;
  const nlohmann::json j = summary(out);
  ASSERT_TRUE(j.contains("fit_residual"));
  EXPECT_LT(j["fit_residual"].get<double>(), 0.03);
  EXPECT_LE(std::abs(j["GF_rel_error"].get<double>()), 1e-8);
  EXPECT_TRUE(fs::exists(out / "target.csv"));
  const ecm::MaterialParams m = ecm::io::loadMaterialFile(material);
  EXPECT_EQ(m.name, "den-fit");
  EXPECT_EQ(m.model, ecm::ModelKind::Enriched);
  EXPECT_EQ(m.softeningModulus, j["Ep"].get<double>());
  EXPECT_EQ(m.softeningExponent, j["n"].get<double>());
  EXPECT_EQ(m.bandWidth, 0.05);
  EXPECT_EQ(m.elastic.poissonRatio, 0.2);
}

TEST_F(EcmCalibrate, YamlInputWorksLikeTheCommandLine) {
  const fs::path in = dir_ / "in.yaml", out = dir_ / "yaml";
  std::ofstream(in) << "# units: mm, N, MPa\nyoungs_modulus: 32000\ntensile_strength: 3.0\nfracture_energy: 0.11\n"
                       "band_width: 0.05\nsoftening_exponent: 0.128\nout: "
                    << out.string() << "\n";
  ASSERT_EQ(run("--input '" + in.string() + "'"), 0) << err_;
  EXPECT_NEAR(summary(out)["Ep"].get<double>(), 8.18, 0.02);
  std::ofstream(in, std::ios::app) << "colour: red\n";
  EXPECT_EQ(run("--input '" + in.string() + "'"), ecm::io::kExitBadInput);
  EXPECT_NE(err_.find(in.string() + ":8: unknown key 'colour'"), std::string::npos) << err_;
}

TEST_F(EcmCalibrate, CrackBandBeyondHCritExitsWithTheNeededStrength) {
  // A computation without a result: the run failed (1), the input is well formed.
  EXPECT_EQ(run("--E 32000 --ft 3.0 --GF 0.11 --n 0.128 --smeared-H 800 --out '" + (dir_ / "sm").string() + "'"),
            ecm::io::kExitRunFailed);
  EXPECT_NE(err_.find("H_crit = 782.2222222 mm"), std::string::npos) << err_;
  EXPECT_NE(err_.find("needed tensile strength = 2.966479395 MPa"), std::string::npos) << err_;
  EXPECT_EQ(run("--E 32000 --ft 3.0 --GF 0.11 --n 0.128 --smeared-H 100 --out '" + (dir_ / "ok").string() + "'"), 0)
      << err_;
}

TEST_F(EcmCalibrate, BadInputExitsTwoNamingValueAndBound) {
  const std::string base = "--E 32000 --ft 3.0 --h 0.05 --out '" + (dir_ / "bad").string() + "' ";
  constexpr int kBadInput = ecm::io::kExitBadInput;
  EXPECT_EQ(run(base + "--GF 0.11 --n 0.5"), kBadInput);
  EXPECT_NE(err_.find("= 0.5 is outside the allowed range (0, 0.5)"), std::string::npos) << err_;
  EXPECT_EQ(run(base + "--GF 0.000001 --n 0.128"), kBadInput);
  EXPECT_NE(err_.find("below the elastic minimum h ft^2/(2E) = 7.03125e-06 N/mm"), std::string::npos) << err_;
  EXPECT_EQ(run(base + "--GF -0.11 --n 0.128"), kBadInput);
  EXPECT_EQ(run(base + "--GF nan --n 0.128"), kBadInput);
  const fs::path csv = dir_ / "two.csv";
  std::ofstream(csv) << "w,sigma\n0,3\n0.01,2\n";
  EXPECT_EQ(run(base + "--GF 0.11 --fit-csv '" + csv.string() + "'"), kBadInput);
  EXPECT_NE(err_.find("at least 3"), std::string::npos) << err_;
  EXPECT_EQ(run(base + "--GF 0.11 --fit spline"), kBadInput);
  EXPECT_EQ(run("--input '" + (dir_ / "no-such.yaml").string() + "'"), kBadInput);
  EXPECT_EQ(run("--no-such-option 1"), kBadInput);
  EXPECT_NE(err_.find("no-such-option"), std::string::npos) << err_;  // CLI11's message
  EXPECT_EQ(run("--help"), ecm::io::kExitDone);
  EXPECT_NE(out_.find("Exit status"), std::string::npos) << out_;
}

TEST_F(EcmCalibrate, AnOutputFolderThatCannotBeUsedIsBadInput) {
  std::ofstream(dir_ / "a-file") << "not a folder\n";
  EXPECT_EQ(run("--E 32000 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 --out '" + (dir_ / "a-file").string() + "'"),
            ecm::io::kExitBadInput);
  EXPECT_NE(err_.find("a-file"), std::string::npos) << err_;
}

TEST_F(EcmCalibrate, AFileThatCannotBeWrittenOnceTheRunHasBegunFailsTheRunAndKeepsTheOutputs) {
  const fs::path out = dir_ / "kept";
  EXPECT_EQ(run("--E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 --out '" + out.string() +
                "' --write-material '" + (dir_ / "no-such-folder" / "m.yaml").string() + "'"),
            ecm::io::kExitRunFailed);
  EXPECT_NE(err_.find("m.yaml"), std::string::npos) << err_;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
}

}  // namespace

namespace {

// --write-umat: ecm's UMAT card for the calibrated law, one *MATERIAL per element size, its
// constants those of the summary (E_p solved for G_F = 0.11 N/mm with the paper's concrete), the
// count declared on *USER MATERIAL equal to the values listed (a forgotten constant crashes
// CalculiX before the UMAT can say so).
TEST_F(EcmCalibrate, WritesTheUmatCardOfTheCalibratedLaw) {
  const fs::path out = dir_ / "umat", card = dir_ / "concrete.inp";
  ASSERT_EQ(run("--E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 --name concrete --out '" + out.string() +
                "' --write-umat '" + card.string() + "' --element-size 2.5,5"),
            0)
      << err_;
  EXPECT_NE(out_.find("UMAT card written to"), std::string::npos) << out_;
  const std::string text = read(card);
  const double ep = summary(out)["Ep"].get<double>();
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> names;
  std::vector<std::vector<double>> constants;
  int declared = 0;
  bool data = false;
  while (std::getline(in, line)) {
    if (line.rfind("*MATERIAL, NAME=", 0) == 0) names.push_back(line.substr(16));
    if (line.rfind("*USER MATERIAL, CONSTANTS=", 0) == 0) {
      declared = std::stoi(line.substr(26));
      constants.emplace_back();
      data = true;
      continue;
    }
    if (line.rfind("*", 0) == 0) data = false;
    if (!data) continue;
    std::istringstream values(line);
    std::string v;
    while (std::getline(values, v, ',')) constants.back().push_back(std::stod(v));
  }
  ASSERT_EQ(names, (std::vector<std::string>{"ABAQUS_CONCRETE_H2p5", "ABAQUS_CONCRETE_H5"}));
  ASSERT_EQ(constants.size(), 2u);
  for (const auto& c : constants) {
    ASSERT_EQ(static_cast<int>(c.size()), declared);
    EXPECT_EQ(c[0], 1.0);
    EXPECT_EQ(c[1], 32000.0);
    EXPECT_EQ(c[2], 0.2);
    EXPECT_EQ(c[3], 3.0);
    EXPECT_EQ(c[4], ep);  // the shortest text that reads back as the same double
    EXPECT_EQ(c[5], 0.128);
    EXPECT_EQ(c[6], 0.05);
  }
  EXPECT_EQ(constants[0][7], 2.5);
  EXPECT_EQ(constants[1][7], 5.0);
}

TEST_F(EcmCalibrate, AUmatCardThatCalculiXCouldNotUseIsRefusedBeforeTheRun) {
  const std::string base = "--E 32000 --nu 0.2 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128 --out '" + (dir_ / "o").string() +
                           "' --write-umat '" + (dir_ / "c.inp").string() + "'";
  EXPECT_EQ(run(base), ecm::io::kExitBadInput);  // CalculiX passes no CELENT: the sizes are needed
  EXPECT_NE(err_.find("--element-size"), std::string::npos) << err_;
  EXPECT_EQ(run(base + " --element-size 0.05"), ecm::io::kExitBadInput);  // H = h
  EXPECT_NE(err_.find("element size H = 0.05"), std::string::npos) << err_;
  EXPECT_EQ(run(base + " --umat-dialect abaqus"), 0) << err_;  // H = 0: Abaqus's CELENT
  EXPECT_NE(read(dir_ / "c.inp").find("*MATERIAL, NAME=CALIBRATED\n"), std::string::npos);
}

}  // namespace
