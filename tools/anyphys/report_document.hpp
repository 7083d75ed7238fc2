#pragma once
// A minimal document model for `anyphys report`: the pages are built once as blocks and rendered
// twice, as self-contained HTML (SVG plots) and as Markdown (PNG plots), so both say the same.
#include <string>
#include <vector>

namespace anyphys::cli {

struct Block {
    enum class Kind { title, section, subsection, paragraph, list, table, image };
    Kind kind = Kind::paragraph;
    std::string text;                              ///< heading or paragraph text; image alt text
    std::vector<std::string> items;                ///< list items; table header
    std::vector<std::vector<std::string>> rows;    ///< table rows
    std::string image;                             ///< plot file name without extension
};

class Document {
public:
    void title(std::string text) { add(Block::Kind::title, std::move(text)); }
    void section(std::string text) { add(Block::Kind::section, std::move(text)); }
    void subsection(std::string text) { add(Block::Kind::subsection, std::move(text)); }
    void paragraph(std::string text) { add(Block::Kind::paragraph, std::move(text)); }
    void list(std::vector<std::string> items);
    void table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows);
    /// A plot: plots/<stem>.svg in HTML, plots/<stem>.png in Markdown.
    void image(std::string stem, std::string alt);

    std::string html() const;
    std::string markdown() const;

private:
    void add(Block::Kind kind, std::string text);
    std::vector<Block> blocks_;
};

}  // namespace anyphys::cli
