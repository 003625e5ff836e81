// The operations' families, one source file each (operations/*_operations.cpp), and what their
// declarations share: the specs of the files they read and write, and the sun's parameters.
// Internal to operations/.
#pragma once

#include <string>
#include <vector>

#include "skylight/operations/operation.h"

namespace skylight::operations::detail {

// The endings of the images the library reads and writes (io/image.h).
inline const std::vector<std::string> kImageFormats{".exr", ".hdr", ".pfm", ".png"};
inline const std::vector<std::string> kFloatImageFormats{".exr", ".hdr", ".pfm"};
inline const std::vector<std::string> kPngFormat{".png"};

// A file the operation reads / writes: required unless `absent` says what happens without it.
ParameterSpec input_file(std::string name, std::string description,
                         std::vector<std::string> formats = {}, std::string absent = {});
ParameterSpec output_file(std::string name, std::string description,
                          std::vector<std::string> formats = {}, std::string absent = {});

// The SPA's parameters a sky takes with a time (solar_position_specs): the place and the
// atmosphere; the SPA's finer ones (delta-ut1, refraction, a surface) are `sun`'s own.
inline constexpr const char* kSolarPositionNames[] = {"lat",      "lon",         "elevation",
                                                      "pressure", "temperature", "delta-t"};

// The relations of the sun's ways: the angles, or a time with the SPA's parameters
// (kSolarPositionNames), each of which needs the time.
std::vector<Relation> solar_position_relations(const std::vector<std::string>& angles);

// The relations of the sun and the solar disc (model_specs()): render's, eval's, the sky's.
std::vector<Relation> model_relations();

// The folder parameter `name` of the request, when given, is an existing folder (a one-line usage
// error otherwise: "--kider 'x': no such folder").
void check_input_folder(const Request& r, const std::string& name);

// `specs` followed by `more`.
std::vector<ParameterSpec> concat(std::initializer_list<std::vector<ParameterSpec>> parts);

std::vector<OperationInfo> sky_operations();         // render, eval
std::vector<OperationInfo> estimate_operations();    // estimate
std::vector<OperationInfo> measured_operations();    // measured
std::vector<OperationInfo> sun_operations();         // sun, daylight
std::vector<OperationInfo> irradiance_operations();  // irradiance
std::vector<OperationInfo> report_operations();      // bench, report
std::vector<OperationInfo> sh_operations();          // sh fit|eval|export|render|error
std::vector<OperationInfo> haze_operations();        // haze coefficients|attenuation|cameras|...
std::vector<OperationInfo> nn_operations();    // nn train|validate|export|animate|study|planet
std::vector<OperationInfo> view_operations();  // view

}  // namespace skylight::operations::detail
