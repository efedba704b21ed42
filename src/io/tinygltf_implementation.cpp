// tinygltf's implementation, alone in its translation unit (kept out of the unity batches, where
// a file including <tiny_gltf.h> first would leave the implementation out), with the options
// io/gltf_file.h sets.
#define TINYGLTF_IMPLEMENTATION
#include "io/gltf_file.h"
