#ifdef GL_ES
precision mediump float;
#endif

uniform sampler2D uSampler;
uniform sampler2D uShadowMap;
uniform vec3 uLightPos;
// A student's own uniforms, set from their JavaScript.
uniform float uLightWidthUV;
uniform int uTechnique;
uniform vec2 uBiasMinMax;

varying highp vec2 vTextureCoord;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;
varying highp float vDepthView;
varying highp vec4 vOffsetFromLight;

float unpack(vec4 rgba) {
  return dot(rgba, vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0));
}

float useShadowMap(sampler2D shadowMap, vec4 shadowCoord, float bias) {
  return step(shadowCoord.z - bias, unpack(texture2D(shadowMap, shadowCoord.xy)));
}

float PCF(sampler2D shadowMap, vec4 coords, float bias) {
  float lit = 0.0;
  for (int x = -1; x <= 1; x++) {
    for (int y = -1; y <= 1; y++) {
      vec2 offset = vec2(float(x), float(y)) * uLightWidthUV / 3.0;
      lit += useShadowMap(shadowMap, vec4(coords.xy + offset, coords.zw), bias);
    }
  }
  return lit / 9.0;
}

void main() {
  vec4 coords = vec4(vOffsetFromLight.xyz / vOffsetFromLight.w * 0.5 + 0.5, 1.0);
  float cosine = max(dot(normalize(vNormal), normalize(uLightPos)), 0.0);
  float bias = mix(uBiasMinMax.y, uBiasMinMax.x, cosine);
  float visibility = uTechnique == 0 ? useShadowMap(uShadowMap, coords, bias) : PCF(uShadowMap, coords, bias);
  float fog = clamp(vDepthView / 500.0, 0.0, 1.0);
  vec3 color = texture2D(uSampler, vTextureCoord).rgb * cosine * visibility;
  gl_FragColor = vec4(mix(color, vec3(0.5), fog), 1.0);
}
