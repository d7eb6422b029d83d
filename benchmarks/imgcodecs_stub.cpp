// A stand-in for libopencv_imgcodecs.so.406 on GPU hosts that have no OpenCV: refit_bench reads
// its photos as .npy and never decodes or encodes an image, but `--max-mb` runs jobs::prune_scene,
// whose folder-of-photos code links these two functions, so the loader wants the library. Each
// aborts, naming itself, should it ever be called. Build it on the host that built refit_bench and
// put it beside the carried OpenCV libraries (LD_LIBRARY_PATH):
//   g++ -O2 -shared -fPIC -I/usr/include/opencv4 -Wl,-soname,libopencv_imgcodecs.so.406 \
//       -o libopencv_imgcodecs.so.406 benchmarks/imgcodecs_stub.cpp -l:libopencv_core.so.406
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace cv {

Mat imread(const std::string& name, int) {
    std::fprintf(stderr, "imgcodecs stub: imread(%s) called; this host has no image codecs\n", name.c_str());
    std::abort();
}

bool imencode(const std::string& extension, InputArray, std::vector<uchar>&, const std::vector<int>&) {
    std::fprintf(stderr, "imgcodecs stub: imencode(%s) called; this host has no image codecs\n", extension.c_str());
    std::abort();
}

}  // namespace cv
