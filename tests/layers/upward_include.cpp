// Must NOT compile: the mesh layer including a header of the render layer. The ctest
// `layers.UpwardIncludeDoesNotBuild` builds this file against quadtri::mesh and passes only
// when the compiler cannot find the header, which is how the layer targets enforce the order.
#include "quadtri/render/camera.h"
