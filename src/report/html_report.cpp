#include "vksplat/report/html_report.hpp"

#include <cctype>
#include <charconv>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "vksplat/report/chart.hpp"

namespace vksplat::report {
namespace {

constexpr const char* kStyle = R"css(
:root { color-scheme: light; }
body { margin: 0; background: #f6f7f9; color: #1d1f23;
       font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", Arial, sans-serif; }
main { max-width: 1480px; margin: 0 auto; padding: 24px 32px 48px; }
h1 { font-size: 26px; margin: 8px 0 16px; }
h2 { font-size: 19px; margin: 32px 0 10px; padding-bottom: 4px; border-bottom: 1px solid #d9dce1; }
p { margin: 8px 0; max-width: 80ch; }
table { border-collapse: collapse; margin: 12px 0; background: #fff; font-size: 14px;
        box-shadow: 0 1px 2px rgba(0,0,0,.08); }
th, td { padding: 5px 12px; border-bottom: 1px solid #e3e5e8; text-align: left; }
th { background: #eef0f3; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tbody tr:nth-child(even) { background: #fafbfc; }
figure { margin: 12px 0; display: inline-block; vertical-align: top; max-width: 100%; }
figure img { display: block; max-width: 100%; height: auto; background: #fff;
             border: 1px solid #e3e5e8; }
figcaption { font-size: 13px; color: #555a61; margin-top: 4px; }
.row { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
.row figure { margin: 0; }
p.note { max-width: none; padding: 8px 14px; border-radius: 4px; }
p.summary { font-weight: 600; font-size: 16px; background: #e8eef6; border-left: 4px solid #0072B2; }
p.warning { background: #fff4cc; border-left: 4px solid #b38600; }
)css";

// Percent-encoding for a relative URL path: unreserved characters and '/' stay, all else is %XX.
std::string url_path(std::string_view path) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (char ch : path) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out += ch;
        } else {
            out += '%';
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    return out;
}

bool looks_numeric(std::string_view cell) {
    while (!cell.empty() && cell.front() == ' ') cell.remove_prefix(1);
    while (!cell.empty() && cell.back() == ' ') cell.remove_suffix(1);
    if (!cell.empty() && cell.back() == '%') cell.remove_suffix(1);
    if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
    if (cell.empty()) return false;
    double value = 0.0;
    const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), value);
    return r.ec == std::errc() && r.ptr == cell.data() + cell.size();
}

std::string figure(const ReportImage& image) {
    if (image.relative_path.empty()) throw std::invalid_argument("HtmlReport: image path is empty");
    if (std::filesystem::path(image.relative_path).is_absolute())
        throw std::invalid_argument("HtmlReport: image path '" + image.relative_path +
                                    "' is absolute; give it relative to the report");
    std::string html = "<figure><img src=\"" + xml_escape(url_path(image.relative_path)) + "\" alt=\"" +
                       xml_escape(image.caption) + "\">";
    if (!image.caption.empty()) html += "<figcaption>" + xml_escape(image.caption) + "</figcaption>";
    return html + "</figure>";
}

}  // namespace

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::add_heading(std::string text) { blocks_.push_back("<h2>" + xml_escape(text) + "</h2>"); }

void HtmlReport::add_paragraph(std::string text) { blocks_.push_back("<p>" + xml_escape(text) + "</p>"); }

void HtmlReport::add_note(std::string text, Note kind) {
    blocks_.push_back(std::string("<p class=\"note ") + (kind == Note::summary ? "summary" : "warning") + "\">" +
                      xml_escape(text) + "</p>");
}

void HtmlReport::add_table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows) {
    for (size_t r = 0; r < rows.size(); ++r)
        if (!header.empty() && rows[r].size() != header.size())
            throw std::invalid_argument("HtmlReport: table row " + std::to_string(r) + " has " +
                                        std::to_string(rows[r].size()) + " cells for " +
                                        std::to_string(header.size()) + " columns");
    std::string html = "<table>\n";
    if (!header.empty()) {
        html += "<thead><tr>";
        for (const std::string& h : header) html += "<th>" + xml_escape(h) + "</th>";
        html += "</tr></thead>\n";
    }
    html += "<tbody>\n";
    for (const auto& row : rows) {
        html += "<tr>";
        for (const std::string& cell : row)
            html += (looks_numeric(cell) ? "<td class=\"num\">" : "<td>") + xml_escape(cell) + "</td>";
        html += "</tr>\n";
    }
    html += "</tbody>\n</table>";
    blocks_.push_back(std::move(html));
}

void HtmlReport::add_image(std::string relative_path, std::string caption) {
    blocks_.push_back(figure({std::move(relative_path), std::move(caption)}));
}

void HtmlReport::add_images_row(std::vector<ReportImage> images) {
    std::string html = "<div class=\"row\">\n";
    for (const ReportImage& image : images) html += figure(image) + "\n";
    blocks_.push_back(html + "</div>");
}

std::string HtmlReport::html() const {
    std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                       "<title>" + xml_escape(title_) + "</title>\n<style>" + kStyle + "</style>\n</head>\n"
                       "<body>\n<main>\n<h1>" + xml_escape(title_) + "</h1>\n";
    for (const std::string& block : blocks_) page += block + "\n";
    page += "</main>\n</body>\n</html>\n";
    return page;
}

void HtmlReport::write(const std::filesystem::path& path, io::WriteMode mode) const {
    const std::string page = html();
    io::write_file_atomically(path, mode, [&](std::ostream& out) { out << page; });
}

}  // namespace vksplat::report
