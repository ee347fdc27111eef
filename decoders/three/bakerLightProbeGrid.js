// Loads what `baker SCENE --format threejs` writes into three.js r187 (npm three@0.187.0) as a
// LightProbeGridWebGL: the grid's box from light_probe_grid.json, its texture from the half-float
// atlas light_probe_grid.bin, as LightProbeGridWebGL would have baked it. Add the result to the
// scene; every lit material (Lambert, Phong, Standard, Physical, Toon) then takes its diffuse
// light from it. docs/ENGINES.md shows it in use.
import { ClampToEdgeWrapping, Data3DTexture, HalfFloatType, LinearFilter, RGBAFormat } from 'three';
import { LightProbeGridWebGL } from 'three/addons/lighting/LightProbeGridWebGL.js';

const SUB_VOLUMES = 7;

// json: the parsed light_probe_grid.json; atlas: the bytes of light_probe_grid.bin (an
// ArrayBuffer or a Uint8Array).
export function lightProbeGridFromBaker( json, atlas ) {
	const [ nx, ny, nz ] = json.resolution;
	const layers = SUB_VOLUMES * ( nz + 2 );
	const bytes = atlas instanceof ArrayBuffer ? new Uint8Array( atlas ) : atlas;
	if ( bytes.byteLength !== nx * ny * layers * 8 ) {
		throw new Error( `light_probe_grid.bin: ${ bytes.byteLength } bytes, but a ${ nx } × ${ ny } × ${ nz } grid's atlas has ${ nx * ny * layers * 8 }` );
	}
	// A copy when the bytes do not start on a 2-byte boundary (halves must be aligned).
	const aligned = bytes.byteOffset % 2 === 0 ? bytes : bytes.slice();
	const texels = new Uint16Array( aligned.buffer, aligned.byteOffset, nx * ny * layers * 4 );
	const grid = new LightProbeGridWebGL( json.width, json.height, json.depth, nx, ny, nz );
	grid.position.fromArray( json.position );
	grid.updateBoundingBox(); // the renderer reads the box, which moving the grid does not update

	const texture = new Data3DTexture( texels, nx, ny, layers );
	texture.type = HalfFloatType;
	texture.format = RGBAFormat;
	texture.minFilter = texture.magFilter = LinearFilter; // Data3DTexture defaults to nearest
	texture.wrapS = texture.wrapT = texture.wrapR = ClampToEdgeWrapping;
	texture.generateMipmaps = false;
	texture.needsUpdate = true;
	grid.texture = texture;
	return grid;
}

// directoryUrl: where the two files are served, e.g. 'volumes/room_threejs/'.
export async function loadBakerLightProbeGrid( directoryUrl ) {
	const base = directoryUrl.endsWith( '/' ) ? directoryUrl : directoryUrl + '/';
	const [ json, atlas ] = await Promise.all( [
		fetch( base + 'light_probe_grid.json' ).then( ( r ) => r.ok ? r.json() : Promise.reject( new Error( `${ base }light_probe_grid.json: ${ r.status }` ) ) ),
		fetch( base + 'light_probe_grid.bin' ).then( ( r ) => r.ok ? r.arrayBuffer() : Promise.reject( new Error( `${ base }light_probe_grid.bin: ${ r.status }` ) ) ),
	] );
	return lightProbeGridFromBaker( json, new Uint8Array( atlas ) );
}
