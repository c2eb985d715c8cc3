// shadowlab's own copy of the framework's interface: the light pass's uniforms, drawn into the
// light's framebuffer.
class ShadowMaterial extends Material {
    constructor(light, translate, scale, vertexShader, fragmentShader) {
        const lightMVP = light.CalcLightMVP(translate, scale);
        super({
            uLightMVP: { type: 'matrix4fv', value: lightMVP },
        }, [], vertexShader, fragmentShader, light.fbo);
    }
}

async function buildShadowMaterial(light, translate, scale, vertexPath, fragmentPath) {
    const vertexShader = await getShaderString(vertexPath);
    const fragmentShader = await getShaderString(fragmentPath);
    return new ShadowMaterial(light, translate, scale, vertexShader, fragmentShader);
}
