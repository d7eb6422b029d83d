// The sweep's tables as CSV: sweep.csv (one row per method and fraction) and sh_degrees.csv.
#include <cstdio>
#include <string>

#include "sweep_parts.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::sweep::detail {
namespace {

// Fixed decimals; infinities as "inf" (Python's float() and pandas read it).
std::string number(double value, int decimals) {
    char text[48];
    std::snprintf(text, sizeof(text), "%.*f", decimals, value);
    return text;
}

// A text field, quoted when it holds a comma, quote or line break (RFC 4180).
std::string field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + '"';
}

// "bytes_compressed_ply": the column of a size format's bytes (a name Python and R take as is).
std::string bytes_column(std::string format) {
    for (char& c : format)
        if (c == '-') c = '_';
    return "bytes_" + format;
}

}  // namespace

void write_sweep_csv(const std::filesystem::path& path, const SweepResult& result, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out << "method,fraction,dropped,gaussians,bytes,megabytes,psnr,delta_psnr,ssim,psnr_vs_unpruned,"
               "ssim_vs_unpruned,ms_per_frame,recover_iterations,recover_seconds,ms_min,ms_max";
        for (const auto& [format, bytes] : result.unpruned.file_bytes) out << ',' << bytes_column(format);
        out << '\n';
        for (const SweepRow& row : result.rows) {
            const ModelMeasure& m = row.measure;
            out << row.method << ',' << fraction_label(row.fraction) << ',' << number(row.dropped, 6)
                << ',' << m.gaussians << ',' << m.bytes << ',' << number(double(m.bytes) / 1e6, 3) << ','
                << number(m.psnr, 4) << ',' << number(row.delta_psnr, 4) << ',' << number(m.ssim, 5) << ','
                << number(m.psnr_vs_unpruned, 4) << ',' << number(m.ssim_vs_unpruned, 5) << ','
                << number(m.ms_per_frame, 3) << ',' << row.recover_iterations << ','
                << number(row.recover_seconds, 2) << ',' << number(m.ms_min, 3) << ',' << number(m.ms_max, 3);
            for (const auto& [format, bytes] : m.file_bytes) out << ',' << bytes;
            out << '\n';
        }
    });
}

void write_sh_csv(const std::filesystem::path& path, const SweepResult& result, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out << "view,sh_degree,psnr\n";
        for (const ShDegreeMeasure& degree : result.sh_degrees) {
            for (size_t v = 0; v < degree.view_psnr.size(); ++v)
                out << field(result.test_view_names[v]) << ',' << degree.degree << ',' << number(degree.view_psnr[v], 4)
                    << '\n';
            out << "mean," << degree.degree << ',' << number(degree.psnr, 4) << '\n';
        }
    });
}

}  // namespace vksplat::sweep::detail
