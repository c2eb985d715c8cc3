#ifdef GL_ES
precision mediump float;
#endif

uniform vec3 uLightPos;
uniform vec3 uCameraPos;

varying highp vec3 vNormal;
varying highp vec2 vTextureCoord;

// Mistake: each channel takes away a share of itself instead of the next channel's carry
// (channels.rgb -= channels.rgb / 256.0, not channels.gba / 256.0): unpack reads a depth off by up
// to a 256th, in a sawtooth, whatever the map keeps. Expected finding: depth_round_trip_wrong.
vec4 pack(float depth) {
  vec4 channels = fract(depth * vec4(1.0, 256.0, 65536.0, 16777216.0));
  channels.rgb -= channels.rgb / 256.0;
  return channels;
}

void main() {
  gl_FragColor = pack(gl_FragCoord.z);
}
