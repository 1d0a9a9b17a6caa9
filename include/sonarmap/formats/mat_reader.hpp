#pragma once
/// @file mat_reader.hpp
/// Reader for the CRAS Micron logs published with the paper (paper §2.1; JoaoCostaIFG/slam,
/// `datasets/dataset_static.mat`), through libmatio.

#include <string>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Reads a CRAS MSIS log: a MAT-file (MATLAB 5, as written by the authors; any version libmatio
/// reads is accepted) with a struct array variable `parsedData`, one element per beam, fields
///   - `time`        1×1 single (double accepted), seconds;
///   - `angle`       1×1 single (double accepted), head angle in degrees;
///   - `step_dist`   1×1 single (double accepted), bin length in metres, > 0;
///   - `intensities` 1×N or N×1, echo intensity per bin, bin 0 nearest: uint8, or double/single
///                   holding integers 0…255 (the published CRAS file stores double).
///
/// Bearing convention: the head is a Tritech Micron and `angle` its SeaNet bearing in degrees
/// (6,400 counts per turn scaled to 360°), so it counts clockwise seen from above with the head's
/// "ahead" at 180° (SeaNet's 3,200; the authors too place angle 180° on their +x axis,
/// `theta = radians(angle + 180)`). `Beam::bearing_rad = radians(angle − 180)` wrapped to
/// [0, 2π), clockwise from ahead as beam.hpp counts, the same as the SeaNet readers give for the
/// same head. The authors draw `x = r cos(theta)`, `y = r sin(theta)` with y up, a view from
/// below for a clockwise head: our maps are their figures mirrored about the x axis. On the CRAS
/// data the first beam (angle 180°) has bearing 0.
///
/// A malformed beam is not an error of the file: it is left out of `SonarLog::beams`, counted in
/// `skipped_beams` and described in `skip_reasons` (element index, field, what was expected).
/// A beam is malformed when a field is missing, empty, complex, of the wrong class or size, when
/// a value is not finite, when `step_dist` ≤ 0, or when its bin count differs from the log's
/// dominant bin count (the most common one; the last beam of the CRAS log has 186 bins instead
/// of 399). Beams keep the file's order; bearings need not be monotonic, times must not decrease
/// from one valid beam to the next.
///
/// Declared sizes are checked before any data is read (libmatio's Mat_VarReadInfo, header only):
/// `parsedData`'s elements × fields × 8 bytes (the least a field takes) and each field's elements ×
/// element size must fit in the file's size, or in 1032 times it for a compressed (zlib, or
/// HDF5 7.3) variable, zlib's largest expansion. So a header claiming 10^9 beams or bins is
/// rejected without allocating for them.
///
/// A file cut short (a full disk, a pulled cable: its last data element runs past the end) is read
/// up to the cut, without libmatio: when that element is `parsedData` (stored plainly, or
/// compressed: what inflates from the bytes there), its whole elements before the cut are read, and
/// one skip reason names the byte, what the element declares and holds, and how many of its
/// declared elements were read. An element is whole when each of its fields is a whole real
/// numeric array.
///
/// libmatio's own log messages are captured (never printed) and appended to the exception text.
///
/// @param path  MAT-file to read.
/// @return      the beams in recording order, with the skipped-beam count and reasons.
/// @throws FileError  when the file cannot be opened, is not a MAT-file or has no MATLAB 5 header
///   (libmatio reads anything else as MATLAB 4, which has no structs), when `parsedData` is
///   missing, not a struct array, empty, or lacks one of the four fields, when a declared size
///   cannot fit in the file (see above), when a valid beam's time is before the previous valid
///   beam's ("times must not go backwards", naming the element), or when no beam of the file is
///   valid (the message then quotes the first beam's problem); for a file cut short, when it is
///   cut before `parsedData`'s first whole element or in another variable ("(cut short ...)"). The
///   message names the file.
SonarLog readCrasMat(const std::string& path);

}  // namespace sonarmap
