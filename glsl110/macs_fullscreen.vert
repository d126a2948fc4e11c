#version 110
// Full-screen pass: the triangle's corners arrive in clip space; macs_uv runs 0..1 over the output,
// so texture2D(input, macs_uv) reads the texel under the pixel being computed.
attribute vec2 macs_position;
varying vec2 macs_uv;

void main()
{
    macs_uv = macs_position * 0.5 + 0.5;
    gl_Position = vec4(macs_position, 0.0, 1.0);
}
