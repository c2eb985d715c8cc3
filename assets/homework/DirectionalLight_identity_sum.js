// Mistake: CalcLightMVP builds the light's view by hand, multiplying a rotation by a translation
// with a helper that sums each product into mat4.create(), the identity, instead of zeros: the
// view gets the identity added. The map then projects the scene along another direction than
// the light looks, so shadows fall one way while the shading is lit from another.
// Expected finding: light_direction_off.
class DirectionalLight {
  constructor(lightIntensity, lightColor, lightPos, focalPoint, lightUp, hasShadowMap, gl) {
    this.mesh = Mesh.cube(setTransform(0, 0, 0, 0.2, 0.2, 0.2, 0));
    this.mat = new EmissiveMaterial(lightIntensity, lightColor);
    this.lightPos = lightPos;
    this.focalPoint = focalPoint;
    this.lightUp = lightUp;
    this.hasShadowMap = hasShadowMap;
    this.fbo = new FBO(gl);
  }

  CalcLightMVP(translate, scale) {
    const model = mat4.create();
    const projection = mat4.create();
    const mvp = mat4.create();
    mat4.translate(model, model, translate);
    mat4.scale(model, model, scale);
    // The light's axes: z points from the focal point back to the light.
    const z = vec3.create();
    vec3.normalize(z, vec3.sub(z, this.lightPos, this.focalPoint));
    const x = vec3.create();
    vec3.normalize(x, vec3.cross(x, this.lightUp, z));
    const y = vec3.create();
    vec3.cross(y, z, x);
    // Column-major: the rotation's rows are the axes; the translation moves the light to 0.
    const rotation = [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, 0, 0, 0, 1];
    const p = this.lightPos;
    const translation = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -p[0], -p[1], -p[2], 1];
    const view = this.multiply(rotation, translation);
    mat4.ortho(projection, -100, 100, -100, 100, 0.01, 400);
    mat4.multiply(mvp, projection, view);
    mat4.multiply(mvp, mvp, model);
    return mvp;
  }

  // a * b, column-major, summed into a fresh matrix.
  multiply(a, b) {
    const out = mat4.create();
    for (let column = 0; column < 4; column++) {
      for (let row = 0; row < 4; row++) {
        for (let k = 0; k < 4; k++) {
          out[column * 4 + row] += a[k * 4 + row] * b[column * 4 + k];
        }
      }
    }
    return out;
  }
}
