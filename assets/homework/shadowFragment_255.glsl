#ifdef GL_ES
precision mediump float;
#endif

uniform vec3 uLightPos;
uniform vec3 uCameraPos;

varying highp vec3 vNormal;
varying highp vec2 vTextureCoord;

// Depth in [0, 1] over four 8-bit channels with 255 steps each, as an RGBA8 texel stores them
// (the framework's pack uses 256: its unpacked depth reads about depth / 255 too far, which
// hides acne like a bias would). Pair it with an unpack that uses 255 too.
vec4 pack(float depth) {
  vec4 channels = fract(depth * vec4(1.0, 255.0, 65025.0, 16581375.0));
  channels.rgb -= channels.gba / 255.0;
  return channels;
}

void main() {
  gl_FragColor = pack(gl_FragCoord.z);
}
