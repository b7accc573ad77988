/// @file animated_png.hpp
/// @brief PNG frames of one size joined into one animated PNG (APNG), without decoding them.
///
/// Chapter 7 shows a short film of the cut; Debian's ffmpeg would make one, at the price of a
/// large dependency for one file. An animated PNG (the APNG extension of PNG, which every current
/// web browser plays, and which a viewer without it shows as its first frame) needs none: its
/// frames are the PNGs' own compressed image data, moved into frame chunks. So we copy each
/// frame's IDAT bytes into an fdAT chunk (or, for the first frame, keep them as IDAT), add the
/// animation control chunk acTL and a frame control chunk fcTL per frame, and recompute the
/// chunks' CRCs. Nothing is decoded or recompressed.
#pragma once

#include <filesystem>
#include <vector>

namespace kerf {

/// Joins `frames` (PNG files of the same width, height, bit depth and colour type, e.g. VTK's)
/// into the APNG `file`, each frame shown `delay_ms` milliseconds, looping forever.
/// @throws InputError `FILE: PNG: PROBLEM` for a frame that is not a PNG or differs in its
///         header from the first, `FILE: write: ...` when the output cannot be written;
///         std::invalid_argument for no frames or a delay outside [1, 65535] ms
void write_animated_png(const std::vector<std::filesystem::path>& frames, const std::filesystem::path& file, int delay_ms);

} // namespace kerf
