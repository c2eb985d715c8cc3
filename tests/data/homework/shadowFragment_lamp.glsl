#ifdef GL_ES
precision mediump float;
#endif

// A lamp's map holds each surface's distance to the lamp over the far plane (as a cube map
// would), not the projection's depth.
uniform vec3 uLightPos;
uniform float uLightFarPlane;

varying highp vec3 vWorldPos;

vec4 pack(float depth) {
  vec4 channels = fract(depth * vec4(1.0, 256.0, 65536.0, 16777216.0));
  channels.rgb -= channels.gba / 256.0;
  return channels;
}

void main() {
  gl_FragColor = pack(length(vWorldPos - uLightPos) / uLightFarPlane);
}
