// ecm-calibrate: parameters of the band's damage law (Eq. (13)) from a fracture energy, a target
// softening curve, or a crack-band element size. A thin main over the calibration library;
// see calibration/README.md. Exit status (io/cli_exit.hpp): 0 done, 1 no result (no crack-band
// E_p exists: H >= H_crit) or an output could not be written, 2 bad input or output folder.
#include <CLI/CLI.hpp>
#include <optional>

#include <iostream>
#include <map>

#include "calibration/calibration_error.hpp"
#include "calibration/calibration_input.hpp"
#include "calibration/calibration_run.hpp"
#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/material_yaml.hpp"
#include "io/output_dir.hpp"
#include "material/parameter_check.hpp"
#include "material/smeared_crack.hpp"

namespace {

using namespace ecm;
using namespace ecm::calibration;

using io::kExitBadInput, io::kExitRunFailed;

// `running` turns true once the input is read and the output folder is ready: a failure from
// there on is the run's (exit 1), one before it bad input (exit 2).
int run(const CalibrationInput& cli, const std::optional<std::filesystem::path>& inputFile, bool& running) {
  CalibrationInput in;
  if (inputFile) in = readCalibrationInput(*inputFile);
  overlay(in, cli);
  const CalibrationPlan plan = planCalibration(in);
  io::prepareOutputDir(plan.out);
  running = true;
  const CalibrationResult result = runCalibration(plan);
  printTable(result, std::cout);
  writeOutputs(result, plan.out);
  std::cout << "  outputs in " << plan.out.string() << ": summary.json, softening.csv"
            << (result.target ? ", target.csv" : "") << ", softening.png\n";
  writeRequestedFiles(result, plan, std::cout);
  return io::kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ecm-calibrate: calibrate the band damage law F(D) of Eq. (13) (units: mm, N, MPa).\n"
      "  solve E_p:   --E 32000 --ft 3.0 --GF 0.11 --h 0.05 --n 0.128\n"
      "  fit n, E_p:  --E 32000 --ft 3.0 --GF 0.11 --h 0.05 --fit hordijk   (or --fit-csv FILE)\n"
      "  forward:     --E 32000 --ft 3.0 --h 0.05 --Ep 8.184 --n 0.128\n"
      "  crack band:  --E 32000 --ft 3.0 --GF 0.11 --n 0.128 --smeared-H 100\n"
      "  UMAT card:   ... --nu 0.2 --write-umat concrete.inp --element-size 2.5   (CalculiX; --umat-dialect abaqus)\n"
      "Exit status: 0 done, 1 no result (no crack-band E_p: H >= H_crit) or an output not written, 2 bad input."};
  app.set_help_flag("--help", "Print this help and exit");

  std::map<std::string, double> values;
  for (const Quantity& q : quantities())
    app.add_option(q.flag, values[q.key], std::string(q.key) + ": " + q.symbol + " (" + q.unit + ")");
  std::optional<std::filesystem::path> inputFile;
  std::string fit, fitCsv, out, writeMaterial, writeUmat, name, hypothesis, dialect;
  std::vector<double> elementSizes;
  app.add_option("--input", inputFile, "YAML input with the same quantities as keys (command line overrides it)");
  app.add_option("--fit", fit, "fit n and E_p to a target curve: hordijk");
  app.add_option("--fit-csv", fitCsv, "fit n and E_p to measured points: CSV of w (mm), sigma (MPa)");
  app.add_option("--out", out, "output folder (default out/calibrate)");
  app.add_option("--write-material", writeMaterial, "write the calibrated material YAML to this file (needs --nu)");
  app.add_option("--write-umat", writeUmat,
                 "write ecm's UMAT card (*MATERIAL, *USER MATERIAL, *DEPVAR) for the calibrated law to this file (needs --nu)");
  app.add_option("--element-size", elementSizes, "H (mm) of the elements the card is for, one *MATERIAL each (2.5,5)")
      ->delimiter(',');
  app.add_option("--umat-dialect", dialect, "calculix (default; needs --element-size) | abaqus (no size: H from CELENT)");
  app.add_option("--name", name, "name of the written material (default calibrated)");
  app.add_option("--hypothesis", hypothesis, "plane_stress (default) | plane_strain, for the written material");

  if (const std::optional<int> status = io::parseCommandLine(app, "ecm-calibrate", argc, argv)) return *status;

  CalibrationInput cli;
  for (const Quantity& q : quantities())
    if (app.count(q.flag) > 0) cli.*q.member = values[q.key];
  if (app.count("--fit") > 0) {
    if (fit != "hordijk") {
      io::printError("ecm-calibrate", "--fit '" + fit + "' is not one of: hordijk (use --fit-csv FILE for measured points)");
      return kExitBadInput;
    }
    cli.fit = fit;
  }
  if (app.count("--fit-csv") > 0) cli.fitCsv = fitCsv;
  if (app.count("--out") > 0) cli.out = out;
  if (app.count("--write-material") > 0) cli.writeMaterial = writeMaterial;
  if (app.count("--write-umat") > 0) cli.writeUmat = writeUmat;
  if (app.count("--element-size") > 0) cli.elementSizes = elementSizes;
  if (app.count("--umat-dialect") > 0) cli.umatDialect = dialect;
  if (app.count("--name") > 0) cli.name = name;
  if (app.count("--hypothesis") > 0) cli.hypothesis = hypothesis;

  bool running = false;
  try {
    return run(cli, inputFile, running);
  } catch (const RegularisationError& e) {
    std::cerr.precision(10);
    std::cerr << io::errorLine("ecm-calibrate", std::string("no softening modulus E_p exists: ") + e.what()) << "  H_crit = " << e.criticalSize
              << " mm\n  needed tensile strength = " << e.requiredStrength << " MPa\n";
    return kExitRunFailed;
  } catch (const io::InputError& e) {
    io::printError("ecm-calibrate", e.what());
    return kExitBadInput;
  } catch (const CalibrationError& e) {
    io::printError("ecm-calibrate", e.what());
    return kExitBadInput;
  } catch (const ParameterError& e) {
    io::printError("ecm-calibrate", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {  // io::OutputError among them
    io::printError("ecm-calibrate", e.what());
    return running ? kExitRunFailed : kExitBadInput;
  }
}
