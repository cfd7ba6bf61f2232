// The comparison functions of OpenGL (alpha, depth and stencil tests, texture comparison),
// shared by the fixed-function shaders and the program stages src/translate/glsl generates.

// `a func b` for func in the order NEVER, LESS, EQUAL, LEQUAL, GREATER, NOTEQUAL, GEQUAL,
// ALWAYS (the GL enums from GL_NEVER).
bool compare(uint func, float a, float b) {
    switch (func) {
    case 0u: return false;
    case 1u: return a < b;
    case 2u: return a == b;
    case 3u: return a <= b;
    case 4u: return a > b;
    case 5u: return a != b;
    case 6u: return a >= b;
    default: return true;
    }
}

