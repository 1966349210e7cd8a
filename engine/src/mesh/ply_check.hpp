// A PLY file is checked to be complete before assimp reads it: assimp 5.2 loops forever on a PLY
// header cut short and aborts (ai_assert) on ASCII data cut short. Facts from the PLY format
// description (Greg Turk, 1994).
#pragma once

#include <string>

namespace tacta::mesh_detail {

// Does nothing unless the file starts with "ply". Throws InputError (file, line for ASCII data)
// when the header is incomplete or malformed, or the data holds fewer values than the header says.
void check_ply_complete(const std::string& path);

}  // namespace tacta::mesh_detail
