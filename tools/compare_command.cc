// `moorsim compare A B`: two outputs compared channel by channel (io/compare.h),
// for regression suites: exit 0 if every channel is within its tolerance, 1 if any differs.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "io/compare.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct CompareFlags {
  std::string a;
  std::string b;
  std::vector<std::string> rtol;
  std::vector<std::string> atol;
  std::vector<std::string> ignore;
  std::string show = "20";
};

int Compare(const CompareFlags& flags) {
  output::CompareOptions options;
  for (const std::string& text : flags.rtol) {
    output::AddTolerance(options, output::ToleranceRule::Kind::kRelative, text);
  }
  for (const std::string& text : flags.atol) {
    output::AddTolerance(options, output::ToleranceRule::Kind::kAbsolute, text);
  }
  for (const std::string& pattern : flags.ignore) {
    options.ignore.push_back(RequireText("--ignore", pattern));
  }
  const int show = ParseInteger("--show", flags.show, 0, 1000000);
  const output::Comparison comparison = output::CompareOutputs(flags.a, flags.b, options);
  output::PrintComparison(comparison, static_cast<std::size_t>(show), std::cout, ": --show");
  return comparison.differences.empty() ? 0 : 1;
}

}  // namespace

Command AddCompareCommand(CLI::App& app) {
  auto flags = std::make_shared<CompareFlags>();
  CLI::App* sub = app.add_subcommand(
      "compare", "compare two run.h5 (or campaign.h5, or runs.csv) channel by channel");
  sub->add_option("A", flags->a,
                  "the output to check: a file, or a directory with run.h5 or runs.csv")
      ->required();
  sub->add_option("B", flags->b, "the reference, of the same kind")->required();
  sub->add_option("--rtol", flags->rtol,
                  "relative tolerance: VALUE (floats' default, 1e-9) or PATTERN=VALUE "
                  "(repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--atol", flags->atol,
                  "absolute tolerance: VALUE (floats' default, 0) or PATTERN=VALUE (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--ignore", flags->ignore, "leave out the channels PATTERN matches (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--show", flags->show, "report at most N differing channels (default 20)");
  sub->footer(
      "\nChannels. In an HDF5 file (run.h5, campaign.h5) every numeric or string dataset is a\n"
      "channel named by its path (/mooring/fairlead_tension); attributes (the program version,\n"
      "the scenario's text and path, units) are not compared. In a runs.csv every column is a\n"
      "channel named by its header (dht.delay), rows matched by their run index. A channel in\n"
      "one output only, of another shape, or numbers in one and text in the other differs.\n"
      "\n"
      "Values. B is the reference. Floats agree if |a - b| <= atol + rtol |b| (default rtol\n"
      "1e-9, atol 0: the same build on the same input gives identical numbers); NaN agrees\n"
      "with NaN only. Integers (HDF5 integer datasets such as detector decisions, csv columns\n"
      "of whole numbers) and text (string datasets, other csv columns) compare exactly unless\n"
      "a pattern gives them a tolerance. An empty field of a numeric csv column reads as NaN.\n"
      "\n"
      "Patterns. PATTERN is a glob ('*', '?', '[...]'; '*' also matches '/') matched against\n"
      "a channel's name and, for a table that names its columns, against NAME/COLUMN\n"
      "(/vessel/pose_true/psi). Of the --rtol (or --atol) patterns that match a value, the\n"
      "last one given wins. A pattern that matches no channel of A or B is an error.\n"
      "\n"
      "Output: one line per differing channel, worst first (its worst value: row, time, column,\n"
      "a, b, |a-b|, allowed), then \"N of M channels differ\" or \"all M channels within\n"
      "tolerance\". Exit codes: 0 all within tolerance, 1 some differ, 2 bad input.\n"
      "\n"
      "Example: moorsim compare out/seed_tapm golden/run.h5 --atol '/vessel/pose_true=5e-5'\n"
      "         --atol '/vessel/pose_true/[xyz]=5e-3' --atol '/mooring/*=2e3'");
  return [flags] { return Compare(*flags); };
}

}  // namespace moorsim::cli
