// `moorsim schema`: the scenario (or campaign) format as a JSON Schema, for editors with
// YAML language support. It is written from the same tables the loader checks against
// (scenarios/schema.h), so the two cannot disagree.
#include <cstdio>
#include <memory>

#include "scenarios/schema.h"
#include "tools/commands.h"

namespace moorsim::cli {

Command AddSchemaCommand(CLI::App& app) {
  auto campaign = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "schema", "print the scenario format as a JSON Schema (draft-07), for editors");
  sub->add_flag("--campaign", *campaign, "the campaign format instead of the scenario format");
  sub->add_flag("--markdown", *markdown,
                "a Markdown table of every key instead (as in scenarios/README.md)");
  sub->footer(
      "\nEvery key with its kind, unit, description, range, choices and default, from the\n"
      "tables `moorsim validate` checks against. Save it next to your files and start each\n"
      "with a modeline that editors with YAML language support read:\n"
      "  moorsim schema > moorsim.schema.json\n"
      "  # yaml-language-server: $schema=moorsim.schema.json\n"
      "The schema checks each key on its own; rules between values (a line that must reach\n"
      "its fairlead, waves too steep for their period) are left to `moorsim validate`.");
  return [campaign, markdown] {
    const scenarios::schema::Block& root =
        *campaign ? scenarios::schema::Campaign() : scenarios::schema::Scenario();
    const std::string text = *markdown
                                 ? scenarios::schema::MarkdownTable(root)
                                 : scenarios::schema::JsonSchema(
                                       root, *campaign ? "moorsim campaign" : "moorsim scenario");
    std::fwrite(text.data(), 1, text.size(), stdout);
    return 0;
  };
}

}  // namespace moorsim::cli
