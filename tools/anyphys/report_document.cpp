// HTML and Markdown rendering of the report's blocks.
#include "report_document.hpp"

#include <sstream>

namespace anyphys::cli {
namespace {

std::string escapeHtml(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

/// Markdown cells and text: '|' would split a table cell, '*' and '_' could start emphasis.
std::string escapeMarkdown(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|' || c == '*' || c == '\\' || c == '<') out += '\\';
        out += c;
    }
    return out;
}

const char* kStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1em}"
    "th,td{border:1px solid #bbb;padding:0.2em 0.6em;text-align:left;font-size:0.9em}"
    "th{background:#eee}h2{border-bottom:2px solid #888;margin-top:2em}"
    "img{max-width:100%;border:1px solid #ddd}";

}  // namespace

void Document::add(Block::Kind kind, std::string text) {
    Block block;
    block.kind = kind;
    block.text = std::move(text);
    blocks_.push_back(std::move(block));
}

void Document::list(std::vector<std::string> items) {
    Block block;
    block.kind = Block::Kind::list;
    block.items = std::move(items);
    blocks_.push_back(std::move(block));
}

void Document::table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows) {
    Block block;
    block.kind = Block::Kind::table;
    block.items = std::move(header);
    block.rows = std::move(rows);
    blocks_.push_back(std::move(block));
}

void Document::image(std::string stem, std::string alt) {
    Block block;
    block.kind = Block::Kind::image;
    block.image = std::move(stem);
    block.text = std::move(alt);
    blocks_.push_back(std::move(block));
}

std::string Document::html() const {
    std::ostringstream out;
    std::string title = "anyphys report";
    for (const Block& b : blocks_)
        if (b.kind == Block::Kind::title) title = b.text;
    out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << escapeHtml(title)
        << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
    for (const Block& b : blocks_) {
        switch (b.kind) {
            case Block::Kind::title: out << "<h1>" << escapeHtml(b.text) << "</h1>\n"; break;
            case Block::Kind::section: out << "<h2>" << escapeHtml(b.text) << "</h2>\n"; break;
            case Block::Kind::subsection: out << "<h3>" << escapeHtml(b.text) << "</h3>\n"; break;
            case Block::Kind::paragraph: out << "<p>" << escapeHtml(b.text) << "</p>\n"; break;
            case Block::Kind::list:
                out << "<ul>\n";
                for (const std::string& item : b.items) out << "<li>" << escapeHtml(item) << "</li>\n";
                out << "</ul>\n";
                break;
            case Block::Kind::table:
                out << "<table>\n<tr>";
                for (const std::string& h : b.items) out << "<th>" << escapeHtml(h) << "</th>";
                out << "</tr>\n";
                for (const auto& row : b.rows) {
                    out << "<tr>";
                    for (const std::string& cell : row) out << "<td>" << escapeHtml(cell) << "</td>";
                    out << "</tr>\n";
                }
                out << "</table>\n";
                break;
            case Block::Kind::image:
                out << "<p><img src=\"plots/" << escapeHtml(b.image) << ".svg\" alt=\"" << escapeHtml(b.text) << "\"></p>\n";
                break;
        }
    }
    out << "</body>\n</html>\n";
    return out.str();
}

std::string Document::markdown() const {
    std::ostringstream out;
    for (const Block& b : blocks_) {
        switch (b.kind) {
            case Block::Kind::title: out << "# " << escapeMarkdown(b.text) << "\n\n"; break;
            case Block::Kind::section: out << "## " << escapeMarkdown(b.text) << "\n\n"; break;
            case Block::Kind::subsection: out << "### " << escapeMarkdown(b.text) << "\n\n"; break;
            case Block::Kind::paragraph: out << escapeMarkdown(b.text) << "\n\n"; break;
            case Block::Kind::list:
                for (const std::string& item : b.items) out << "- " << escapeMarkdown(item) << "\n";
                out << "\n";
                break;
            case Block::Kind::table: {
                const auto line = [&](const std::vector<std::string>& cells) {
                    out << "|";
                    for (const std::string& cell : cells) out << " " << escapeMarkdown(cell) << " |";
                    out << "\n";
                };
                line(b.items);
                out << "|";
                for (std::size_t i = 0; i < b.items.size(); ++i) out << "---|";
                out << "\n";
                for (const auto& row : b.rows) line(row);
                out << "\n";
                break;
            }
            case Block::Kind::image: out << "![" << escapeMarkdown(b.text) << "](plots/" << b.image << ".png)\n\n"; break;
        }
    }
    return out.str();
}

}  // namespace anyphys::cli
