# Installation and the exported CMake package (filled by the engine core work).
