#pragma once
// Scene files other than the INRIA .ply, and one entry point that picks the reader or writer by
// extension or by name.
//
//   format name       extension        read  write  what it is
//   "ply"             .ply             yes   yes    INRIA 3DGS PLY (io/ply.hpp); reading also accepts a
//                                                   compressed PLY, told apart by its header
//   "compressed-ply"  .compressed.ply  yes   yes    PlayCanvas compressed PLY (chunks of 256 splats)
//   "splat"           .splat           yes   yes    antimatter15 .splat: 32 bytes a splat, SH degree 0
//   "spz"             .spz             yes   yes    Niantic SPZ, versions 2, 3 and 4; writes 3
//   "spz-v4"          (name only)      yes   yes    the same, written as version 4 (zstd)
//   "sog"             .sog, meta.json  yes   yes    PlayCanvas SOG: WebP textures and a meta.json, zipped
//                                                   (.sog) or in a folder (a path named meta.json)
//   "gltf"            .glb             yes   yes    binary glTF 2.0 with KHR_gaussian_splatting (draft)
//   "gsplat-pt"       .pt .pth         yes   no     gsplat checkpoint saved by torch.save (zip + pickle)
//
// SPZ is written as version 3 unless version 4 is asked for, although Niantic's library and
// splat-transform 2.x write 4 by default: every SPZ reader reads 3 (those that read 4 too: Niantic's
// library since its 3.0, splat-transform and so SuperSplat, three.js, LichtFeld Studio), while 4 is
// refused by the readers that predate it (Niantic's library before its 3.0, viewers with a decoder
// of their own that stops at 3), and it buys little here: with our 8-bit SH, version 4 is 3 to 5%
// smaller (snowmiku 2.61 MB against 2.69, lego 10.76 against 11.26; splat-transform's own pair,
// with its coarser SH, differ by 3.5%).
//
// Every reader throws InputError naming the file and what is wrong with it (truncated, wrong magic
// or version, counts that overflow or disagree with the file's size, ...). Every writer goes
// through write_file_atomically, so no half-written file is ever left behind.
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::io {

// ---- antimatter15 .splat ----------------------------------------------------------------------
// 32 bytes a splat, little-endian, no header: position f32x3, scale f32x3 (linear), RGBA u8x4
// (colour = 0.5 + SH_C0 * f_dc, alpha = sigmoid(opacity), each times 255), quaternion u8x4 (w, x, y,
// z, each q * 128 + 128). Reading gives SH degree 0, normalised quaternions and log scales; an alpha
// of 0 or 255 becomes a logit of -/+kMaxOpacityLogit. Writing drops SH above the DC term.
GaussianCloud read_splat(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);
void write_splat(const GaussianCloud& cloud, const std::filesystem::path& path,
                 WriteMode mode = WriteMode::refuse_existing);

// ---- Niantic .spz -----------------------------------------------------------------------------
// Reads versions 2 (quaternion as x, y, z bytes), 3 (quaternion "smallest three" in 4 bytes) and 4
// (3's values, each attribute a zstd frame of its own after a plain header and table of contents),
// SH degree 0 to 3. SPZ keeps its splats in RUB axes (y up, z back) where PLY and the cloud use RDF
// (y down, z forward): reading and writing turn them half a turn about x (y, z, the quaternion's y
// and z, and the SH odd in them change sign), as Niantic's library and splat-transform do. Version
// 4 may say otherwise in its coordinate-system extension: RUB and RDF are honoured, any other
// system is refused, and other extensions are noted as ignored. Versions 2 and 3 with extensions
// (flag 0x2) are refused. An alpha of 0 or 255 becomes -/+kMaxOpacityLogit.
GaussianCloud read_spz(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);
// Writes `version` (3 or 4) with 12 fractional bits for positions (fewer when a coordinate would not
// fit in 24 bits) and SH quantised to the full 8 bits, in RUB and without extensions. Throws
// InputError for non-finite positions or coordinates beyond 2^23 (which SPZ cannot hold).
void write_spz(const GaussianCloud& cloud, const std::filesystem::path& path,
               WriteMode mode = WriteMode::refuse_existing, int version = 3);

// ---- PlayCanvas compressed .ply -----------------------------------------------------------------
// Element `chunk` (min/max of position and log scale, optionally of colour, per 256 splats), element
// `vertex` with packed_position (11-10-11), packed_rotation (2 + 10-10-10, smallest three),
// packed_scale (11-10-11) and packed_color (8-8-8-8 RGBA), and optionally element `sh` with u8
// f_rest_* coefficients.
GaussianCloud read_compressed_ply(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);
// Writes the layout above as splat-transform does: the splats reordered along a Morton curve of
// their positions (so each chunk covers a small box), chunk ranges with colour, SH as bytes over
// [-4, 4]. Per splat that quantises positions and log scales to 1/2047 (x, z) and 1/1023 (y) of
// their chunk's range, colours to 1/255 of theirs, opacity (after the sigmoid) to 1/255, rotations
// to 10 bits of each smaller component and SH to 8/256. Throws InputError for non-finite positions.
void write_compressed_ply(const GaussianCloud& cloud, const std::filesystem::path& path,
                          WriteMode mode = WriteMode::refuse_existing);
// True when the file is a PLY whose header declares the compressed layout (a `chunk` element and a
// `vertex` element with packed_position). Throws InputError if the file is not a PLY at all.
bool is_compressed_ply(const std::filesystem::path& path);

// ---- PlayCanvas SOG (.sog, or meta.json beside its textures) -----------------------------------
// Version 2, as splat-transform 2.x and SuperSplat write it and the PlayCanvas engine reads it: per
// splat, texels of lossless WebP textures hold the position (16 bits an axis of a log encoding,
// sign(x) ln(|x| + 1), over its range), the rotation ("smallest three" in 8 bits each), indices
// into codebooks of 256 log scales and 256 f_dc values, the opacity (8 bits after the sigmoid) and
// an index into a palette of higher-SH vectors, whose values index a codebook of their own.
// Axes as in the PLY. Reading takes a .sog zip or a meta.json (told apart by content); the
// textures must be plain names beside meta.json. Version 1 (no "version" key) is refused.
GaussianCloud read_sog(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);
// Writes a .sog zip (entries stored: WebP is compressed already), or, for a path named meta.json,
// meta.json and its textures into that folder (every file checked for `mode` before any is
// written). Splats in Morton order; codebooks by k-means (OpenCV). The SH palette holds at most
// 4096 entries, where splat-transform fits up to 65536 on a GPU: snowmiku's 57,694 splats take
// 38 s of CPU time, and its renders lose 0.97 dB PSNR against the photos (28.51 -> 27.54 dB, of
// which 0.85 the palette; SH degree 0 alone would lose 4.7 dB). Throws InputError for non-finite
// values or a quaternion of length 0.
void write_sog(const GaussianCloud& cloud, const std::filesystem::path& path,
               WriteMode mode = WriteMode::refuse_existing);

// ---- binary glTF (.glb) with KHR_gaussian_splatting -------------------------------------------
// One mesh primitive of mode POINTS: POSITION, the extension's ROTATION (unit quaternion, glTF's
// x, y, z, w order), SCALE (linear), OPACITY (after the sigmoid) and SH_DEGREE_l_COEF_m (the raw
// f_dc and f_rest, all floats), and COLOR_0 (bytes: the DC colour, decoded from sRGB as glTF's
// linear vertex colours are, and the opacity) for viewers without the extension. Axes: glTF's
// (y up, z forward), which the extension asks for and splat-transform 2.x writes, turned half a
// turn about z from the PLY's (x, y, the quaternion's x and y and the SH odd in them change
// sign), with no node transform; reading turns them back.
// Reading takes every primitive with the extension (float or, where the extension allows, normalised
// integer attributes, joined into one cloud); refuses node transforms, sparse or external data,
// and kernels other than "ellipse". .gltf (JSON with external buffers) is neither read nor written.
GaussianCloud read_gltf(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);
// Round trip: positions and SH exact; log scales within 1e-6; opacity within float rounding after
// the sigmoid (so logits above about 17.3, whose opacity rounds to 1, come back as
// kMaxOpacityLogit); quaternions normalised. COLOR_0 is not read back (SH_DEGREE_0 is the colour).
// Throws InputError for an empty cloud, non-finite positions, quaternions of length 0, or more
// than the GLB's 4 GiB.
void write_gltf(const GaussianCloud& cloud, const std::filesystem::path& path,
                WriteMode mode = WriteMode::refuse_existing);

// ---- gsplat checkpoint .pt (read only) --------------------------------------------------------
// A torch.save zip archive whose pickle holds {"splats": {means [N,3], quats [N,4] (w,x,y,z),
// scales [N,3] (log), opacities [N] (logit), sh0 [N,1,3], shN [N,K,3]}, ...} (or those tensors at
// the top level). Tensors may be float32, float16, bfloat16 or float64, of any strides and storage
// offsets; entries may be stored or deflated. No Python is involved.
GaussianCloud read_gsplat_checkpoint(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);

// ---- any scene file ---------------------------------------------------------------------------
// The format names read_scene and write_scene accept, in the order above.
std::vector<std::string> scene_formats();
// The format of `path` by its extension (case-insensitive; ".compressed.ply" names "compressed-ply",
// a file named meta.json "sog");
// for any .ply the header decides between "ply" and "compressed-ply" when the file exists. Throws
// InputError, listing the supported extensions, for any other extension.
std::string scene_format_of(const std::filesystem::path& path);
// The format `format` names (case-insensitive), or when it is empty the one `path`'s extension
// names ("compressed-ply" for .compressed.ply, "ply" for any other .ply). It never opens the file:
// what a writer goes by, since a file about to be replaced has no say in what replaces it. Throws
// InputError like scene_format_of, or for an unknown format name.
std::string scene_format_named(const std::filesystem::path& path, const std::string& format = "");

// Reads a scene in the format named by `format`, or by the extension when `format` is empty.
// "ply", and a .ply by its extension (.compressed.ply too), read either PLY flavour: the header
// decides. Notes (ignored properties, skipped data, what
// a format could not hold) are appended to `notes`.
GaussianCloud read_scene(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr,
                         std::string format = "");
// What write_scene checks before it writes, for commands to call before any work: the format
// (as write_scene chooses it, returned) is one it writes, and io::check_writable passes. The
// refusal names the file and lists the extensions that can be written.
std::string check_scene_writable(const std::filesystem::path& path, WriteMode mode = WriteMode::refuse_existing,
                                 const std::string& format = "");
// Writes a scene in any writable format of the table above (by extension when `format` is empty).
// The read-only formats, and unknown ones, give InputError.
void write_scene(const GaussianCloud& cloud, const std::filesystem::path& path,
                 WriteMode mode = WriteMode::refuse_existing, std::string format = "");

}  // namespace vksplat::io
