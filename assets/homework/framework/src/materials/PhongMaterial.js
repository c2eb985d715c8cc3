// shadowlab's own copy of the framework's interface: the camera pass's uniforms.
class PhongMaterial extends Material {
    constructor(color, specular, light, translate, scale, vertexShader, fragmentShader) {
        const lightMVP = light.CalcLightMVP(translate, scale);
        const lightIntensity = light.mat.GetIntensity();
        super({
            uSampler: { type: 'texture', value: color },
            uKs: { type: '3fv', value: specular },
            uLightIntensity: { type: '3fv', value: lightIntensity },
            uShadowMap: { type: 'texture', value: light.fbo },
            uLightMVP: { type: 'matrix4fv', value: lightMVP },
        }, [], vertexShader, fragmentShader);
    }
}

async function buildPhongMaterial(color, specular, light, translate, scale, vertexPath, fragmentPath) {
    const vertexShader = await getShaderString(vertexPath);
    const fragmentShader = await getShaderString(fragmentPath);
    return new PhongMaterial(color, specular, light, translate, scale, vertexShader, fragmentShader);
}
