// Whether WebGL runs in software (SwiftShader, llvmpipe, ...): the 3D view then skips
// multisampling, which costs a software rasterizer several times the shading of a frame.

let cached: boolean | null = null;

export function isSoftwareWebGL(): boolean {
  if (cached !== null) return cached;
  cached = false;
  const gl = document.createElement("canvas").getContext("webgl2");
  if (!gl) return cached;
  const info = gl.getExtension("WEBGL_debug_renderer_info");
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  cached = /swiftshader|llvmpipe|softpipe|software/i.test(name);
  gl.getExtension("WEBGL_lose_context")?.loseContext(); // give the context back now
  return cached;
}
