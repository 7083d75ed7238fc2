// `anyphys schema --markdown` prints the key tables of docs/scene-format.md from the field table
// (anyphys/schema); `--update FILE` rewrites those tables in FILE between their markers, keeping
// the prose around them.
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "anyphys/fields/schema_markdown.hpp"
#include "cli.hpp"

namespace anyphys::cli {

Command addSchemaCommand(CLI::App& parent) {
    auto update = std::make_shared<std::string>();
    auto markdown = std::make_shared<bool>(true);
    CLI::App* app = parent.add_subcommand("schema", "Print the scene-file key tables generated from the field table");
    app->add_flag("--markdown", *markdown, "Print the tables as markdown, each between its doc markers (the default)");
    app->add_option("--update", *update, "Rewrite the marked tables of this markdown file (docs/scene-format.md)");
    // The command owns both values: CLI11 writes through the references above when it parses.
    return {app, [update, markdown] {
                if (update->empty()) {
                    std::cout << schema::markdown(schema::allMarkdownTables());
                    return 0;
                }
                std::ifstream in(*update, std::ios::binary);
                if (!in) throw Error(ErrorKind::Io, "", *update + ": cannot read");
                std::ostringstream text;
                text << in.rdbuf();
                std::vector<std::string> missing;
                const std::string doc = schema::updateMarkdown(text.str(), missing, schema::allMarkdownTables());
                if (!missing.empty())
                    throw Error(ErrorKind::InvalidArgument, "", *update + ": no markers for the tables " + join(missing));
                writeFile(*update, doc);
                return 0;
            }};
}

}  // namespace anyphys::cli
