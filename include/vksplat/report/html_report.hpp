#pragma once
// report.html: headings, text, tables and pictures (charts, comparison sheets) on one page. The
// page holds its own styles and no scripts; pictures are referenced by paths relative to the
// report, so the results folder can be moved or shared whole and opened in any browser.
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/io/write_mode.hpp"

namespace vksplat::report {

struct ReportImage {
    std::string relative_path;  // from the report's folder, e.g. "charts/psnr.svg"
    std::string caption;        // also the picture's alt text
};

// Blocks are shown in the order they are added. All text is HTML-escaped, so names from scene
// files or cameras cannot break the page.
class HtmlReport {
public:
    explicit HtmlReport(std::string title);

    void add_heading(std::string text);
    void add_paragraph(std::string text);
    // A paragraph that stands out: a summary (bold, on a blue-grey band) or a warning (on yellow,
    // with a dark yellow edge), e.g. the one-line result at the top of a report.
    enum class Note { summary, warning };
    void add_note(std::string text, Note kind);
    // A table with a header row (none when header is empty). Every row must have as many cells as
    // the header (any count when there is no header), else std::invalid_argument. Cells that read
    // as numbers (e.g. "31.42", "-3", "1.5e6", "12.5%") are right-aligned.
    void add_table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows);
    // A picture with a caption under it, shown at its own size or shrunk to the page's width.
    // Throws std::invalid_argument for an empty or absolute path. Characters outside
    // [A-Za-z0-9._~/-] are percent-encoded, so any file name works.
    void add_image(std::string relative_path, std::string caption);
    // Pictures side by side, wrapping onto further lines when the window is narrow.
    void add_images_row(std::vector<ReportImage> images);

    const std::string& title() const { return title_; }
    // The whole page.
    std::string html() const;
    // Writes html() to `path` (usually <results>/report.html) through io::write_file_atomically.
    void write(const std::filesystem::path& path, io::WriteMode mode) const;

private:
    std::string title_;
    std::vector<std::string> blocks_;  // HTML fragments, already escaped
};

}  // namespace vksplat::report
