#include "vksplat/io/dataset.hpp"

#include <nlohmann/json.hpp>

#include "io/colmap_model.hpp"
#include "io/undistort.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

void read_colmap(Dataset& data, const fs::path& folder, uint64_t test_every) {
    data.format = "colmap";
    const fs::path model = fs::exists(folder / "sparse" / "0") ? folder / "sparse" / "0" : folder / "sparse";
    detail::ColmapCameras colmap = detail::read_colmap_lens_cameras(model);
    data.undistortion = detail::undistort_cameras(colmap, data.notices);
    data.cameras = std::move(colmap.cameras);
    for (const auto& entry : fs::directory_iterator(model))
        if (entry.is_regular_file()) data.files.push_back(entry.path());
    data.points = read_sfm_points(model, &data.warnings);
    // The reference's llffhold: every test_every-th camera by image name (read sorted) is held out.
    for (size_t i = 0; i < data.cameras.size(); ++i)
        data.cameras[i].split = test_every > 0 && i % test_every == 0 ? "test" : "train";
    data.images_dir = folder / "images";
}

void read_nerf(Dataset& data, const fs::path& folder) {
    data.format = "nerf-synthetic";
    for (const char* split : {"train", "test"}) {
        const fs::path file = folder / ("transforms_" + std::string(split) + ".json");
        data.files.push_back(file);
        if (!fs::exists(file)) continue;  // a set without test views
        for (Camera& camera : read_nerf_transforms(file)) {
            camera.split = split;
            data.cameras.push_back(std::move(camera));
        }
    }
    data.images_dir = folder;
}

}  // namespace

Dataset read_dataset(const fs::path& folder, uint64_t test_every) {
    if (!fs::is_directory(folder)) throw InputError(folder.string(), "is not a folder");
    Dataset data;
    if (fs::exists(folder / "sparse" / "0") || fs::exists(folder / "sparse")) {
        read_colmap(data, folder, test_every);
    } else if (fs::exists(folder / "transforms_train.json")) {
        read_nerf(data, folder);
    } else if (fs::exists(folder / "cameras.json")) {
        data.format = "inria";
        data.cameras = read_inria_cameras(folder / "cameras.json");
        data.files = {folder / "cameras.json"};
        data.images_dir = folder / "images";
    } else {
        throw InputError(folder.string(), "holds neither a COLMAP model (sparse/0), NeRF transforms "
                                          "(transforms_train.json) nor an INRIA cameras.json");
    }
    return data;
}

void write_inria_cameras(const fs::path& path, const std::vector<Camera>& cameras, WriteMode mode) {
    nlohmann::json list = nlohmann::json::array();
    for (size_t id = 0; id < cameras.size(); ++id) {
        const Camera& camera = cameras[id];
        const glm::dmat3 to_world = glm::transpose(camera.rotation);
        const glm::dvec3 centre = camera.centre();
        nlohmann::json rotation = nlohmann::json::array();
        for (int r = 0; r < 3; ++r) rotation.push_back({to_world[0][r], to_world[1][r], to_world[2][r]});
        nlohmann::json entry{{"id", id},          {"img_name", camera.name},
                             {"width", camera.width}, {"height", camera.height},
                             {"position", {centre.x, centre.y, centre.z}},
                             {"rotation", rotation},  {"fx", camera.fx},
                             {"fy", camera.fy},       {"cx", camera.cx},
                             {"cy", camera.cy}};
        if (!camera.split.empty()) entry["split"] = camera.split;
        list.push_back(std::move(entry));
    }
    write_file_atomically(path, mode, [&](std::ostream& out) { out << list.dump(2) << '\n'; });
}

}  // namespace vksplat::io
