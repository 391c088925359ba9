// Prepended by online/ to every GL program (after the #version line): the GLSL side of
// shaders/glsl_prelude.h, so that shared .glsl files compile in both languages.
#define OUT(type) out type
#define INOUT(type) inout type
