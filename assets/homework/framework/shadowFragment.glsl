#ifdef GL_ES
precision mediump float;
#endif

uniform vec3 uLightPos;
uniform vec3 uCameraPos;

varying highp vec3 vNormal;
varying highp vec2 vTextureCoord;

// Depth in [0, 1] spread over four 8-bit channels, the finest last.
vec4 pack(float depth) {
  vec4 channels = fract(depth * vec4(1.0, 256.0, 65536.0, 16777216.0));
  // What a channel holds beyond its 8 bits is the next channel's business.
  channels.rgb -= channels.gba / 256.0;
  return channels;
}

void main() {
  gl_FragColor = pack(gl_FragCoord.z);
}
