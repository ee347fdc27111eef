// The page `baker view` writes: a volume over its glTF scene, one sphere per probe shaded per
// pixel by the volume's irradiance for that pixel's normal (the GLSL port of the decoders),
// slices of the irradiance for a chosen normal, probe states, relocations, sky visibility, an
// exposure with its colour bar, and a click that prints what `baker sample` would at that point.
//
// What is shown, per pixel: sRGB(clamp(E(n)/π · exposure, 0, 1)) for irradiance (what a white
// Lambertian surface would reflect), sRGB(clamp(V(n), 0, 1)) for sky visibility.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { BasisDecoder, blendProbes, finestLevelNeighbourhood, leakWeight, probeNeighbourhood } from '../../decoders/baker_irradiance.js';
import { BAKER_IRRADIANCE_GLSL, bakerUniforms, probeTexture } from '../../decoders/baker_irradiance_webgl.js';

const MODE_IRRADIANCE = 0, MODE_STATES = 1, MODE_VISIBILITY = 2;
// Probe states 0 (inside geometry, filled from neighbours), 1 (valid), 2 (relocated), 3 (on the
// border of an adaptive volume's level: the coarser levels' value there), in sRGB.
const STATE_COLOURS = [ [ 0xea, 0x43, 0x35 ], [ 0x34, 0xa8, 0x53 ], [ 0xfb, 0xbc, 0x04 ], [ 0x42, 0x85, 0xf4 ] ];
const AXES = { '+X': [ 1, 0, 0 ], '-X': [ - 1, 0, 0 ], '+Y': [ 0, 1, 0 ], '-Y': [ 0, - 1, 0 ], '+Z': [ 0, 0, 1 ], '-Z': [ 0, 0, - 1 ] };

const $ = ( id ) => document.getElementById( id );

function linearToSrgb( v ) {
	const c = Math.min( Math.max( v, 0 ), 1 );
	return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow( c, 1 / 2.4 ) - 0.055;
}

// Each level holds some of its grid's probes (a uniform volume: one level holding all), one row
// each: `probeIndex` gives a row's probe index on the level's grid (null: the row is the probe),
// `rowOfProbe` the other way.
async function loadVolume() {
	const answer = await fetch( 'volume.json' );
	if ( ! answer.ok ) throw new Error( `volume.json: ${ answer.status }` );
	const info = await answer.json();
	const response = await fetch( info.binary.file );
	if ( ! response.ok ) throw new Error( `${ info.binary.file }: ${ response.status }` );
	const bytes = await response.arrayBuffer();
	const set = info.reconstruction.function_sets[ 0 ];
	const decoder = new BasisDecoder( info.basis, set.sharpness ?? 0 );
	if ( ! decoder.valid ) throw new Error( `basis ${ info.basis } is not one this page decodes` );
	if ( set.type === 'spherical-gaussians' ) decoder.setLobeAxes( set.axes );
	const levels = info.levels.map( ( level ) => {
		const section = ( name, Type ) => level.sections[ name ] ? new Type( bytes, level.sections[ name ].byte_offset, level.sections[ name ].count ) : null;
		const ijk = section( 'probes', Int32Array );
		let probeIndex = null, rowOfProbe = null;
		if ( ijk ) {
			const [ nx, ny ] = level.dims;
			probeIndex = new Float64Array( level.rows );
			rowOfProbe = new Map();
			for ( let r = 0; r < level.rows; ++ r ) {
				probeIndex[ r ] = ijk[ 3 * r ] + nx * ( ijk[ 3 * r + 1 ] + ny * ijk[ 3 * r + 2 ] );
				rowOfProbe.set( probeIndex[ r ], r );
			}
		}
		return {
			...level,
			subBricksHeld: section( 'sub_bricks_held', Uint8Array ),
			coefficients: section( 'coefficients', Float32Array ),
			visibility: section( 'visibility', Float32Array ),
			states: section( 'states', Int32Array ),
			offsets: section( 'offsets', Float32Array ),
			distanceMoments: section( 'distance_moments', Float32Array ),
			probeIndex,
			rowOfProbe,
		};
	} );
	levels.forEach( ( level, l ) => { level.coveredBy = finerLevelsHolding( levels, l ); } );
	// The box the levels' probes span together (an adaptive volume's levels reach out to it by
	// different margins), and its finest spacing.
	const box = {
		lo: [ 0, 1, 2 ].map( ( a ) => Math.min( ...levels.map( ( l ) => l.origin[ a ] ) ) ),
		hi: [ 0, 1, 2 ].map( ( a ) => Math.max( ...levels.map( ( l ) => l.origin[ a ] + l.spacing * Math.max( l.dims[ a ] - 1, 1e-3 ) ) ) ),
		spacing: Math.min( ...levels.map( ( l ) => l.spacing ) ),
	};
	return { info, decoder, levels, box };
}

const probeOfRow = ( level, row ) => ( level.probeIndex ? level.probeIndex[ row ] : row );
const rowOfProbe = ( level, probe ) => ( level.rowOfProbe ? level.rowOfProbe.get( probe ) ?? - 1 : probe );

function probePosition( level, p ) {
	const [ nx, ny ] = level.dims;
	const ijk = [ p % nx, Math.floor( p / nx ) % ny, Math.floor( p / ( nx * ny ) ) ];
	return new THREE.Vector3( ...ijk.map( ( i, a ) => level.origin[ a ] + level.spacing * i ) );
}

// E(n) and V(n) at a world position, interpolated as `baker sample` does: in an adaptive volume,
// on the finest level whose probes around the position are held; leak-aware (`baker sample
// --leak-aware`, for a surface of that normal at the position), each probe's weight times the
// leak weight its distance map gives, seen from where it was baked, then normalised.
function sampleAt( volume, position, normal, leakAware = false ) {
	const { info, decoder, levels } = volume;
	const around = levels.length === 1 ? { level: 0, ...probeNeighbourhood( position, levels[ 0 ].origin, levels[ 0 ].spacing, levels[ 0 ].dims ) } : finestLevelNeighbourhood( position, levels );
	const level = levels[ around.level ];
	const rows = { probe: around.probe.map( ( p, c ) => ( around.weight[ c ] === 0 ? 0 : rowOfProbe( level, p ) ) ), weight: around.weight.slice() };
	if ( rows.probe.some( ( r ) => r < 0 ) ) throw new Error( `level ${ around.level } lacks a probe it should hold around ${ position }` );
	if ( leakAware && level.distanceMoments ) {
		const [ nx, ny ] = level.dims, perProbe = info.distance_map.values_per_probe;
		let changed = false;
		rows.probe.forEach( ( r, c ) => {
			if ( rows.weight[ c ] === 0 ) return;
			const p = around.probe[ c ], ijk = [ p % nx, Math.floor( p / nx ) % ny, Math.floor( p / ( nx * ny ) ) ];
			const baked = ijk.map( ( i, a ) => level.origin[ a ] + level.spacing * i + level.offsets[ 3 * r + a ] );
			const leak = leakWeight( info.distance_map, level.distanceMoments, baked, position, normal, level.spacing, r * perProbe );
			if ( leak === 1 ) return;
			rows.weight[ c ] *= leak;
			changed = true;
		} );
		const total = rows.weight.reduce( ( sum, w ) => sum + w, 0 );
		if ( changed && total > 0 ) rows.weight = rows.weight.map( ( w ) => w / total );
	}
	const e = decoder.irradiance( blendProbes( level.coefficients, rows, decoder.coefficientsPerProbe ), normal );
	const v = info.visibility_per_probe > 0 ? decoder.visibility( blendProbes( level.visibility, rows, info.visibility_per_probe ), normal ) : null;
	return { irradiance: e, visibility: v };
}

function probeMaterial( volume, level, renderer ) {
	const texture = probeTexture( level.coefficients, volume.info.visibility_per_probe > 0 ? level.visibility : null, volume.decoder, level.rows );
	const limit = renderer.capabilities.maxTextureSize;
	if ( texture.height > limit ) throw new Error( `the probes need a ${ texture.width } × ${ texture.height } texture; this browser's WebGL takes ${ limit } rows` );
	const data = new THREE.DataTexture( texture.data, texture.width, texture.height, THREE.RGBAFormat, THREE.FloatType );
	data.needsUpdate = true;
	const uniforms = { bakerProbes: { value: data }, mode: { value: MODE_IRRADIANCE }, exposure: { value: 1 } };
	for ( const [ name, { value } ] of Object.entries( bakerUniforms( volume.decoder, texture ) ) ) {
		uniforms[ name ] = { value: value instanceof Float32Array ? Array.from( { length: value.length / 3 }, ( _, i ) => new THREE.Vector3( value[ 3 * i ], value[ 3 * i + 1 ], value[ 3 * i + 2 ] ) ) : value };
	}
	const states = STATE_COLOURS.map( ( c ) => `vec3(${ c.map( ( x ) => ( x / 255 ).toFixed( 6 ) ).join( ', ' ) })` ).join( ', ' );
	return new THREE.ShaderMaterial( {
		glslVersion: THREE.GLSL3,
		uniforms,
		vertexShader: /* glsl */ `
in float probeState;
out vec3 worldNormal;
flat out int probe;
flat out int state;
void main() {
  probe = gl_InstanceID;  // instance r is the level's row r
  state = int( probeState + 0.5 );
  mat4 world = modelMatrix * instanceMatrix;
  worldNormal = mat3( world ) * normal;
  gl_Position = projectionMatrix * viewMatrix * world * vec4( position, 1.0 );
}`,
		fragmentShader: /* glsl */ `
precision highp int;
${ BAKER_IRRADIANCE_GLSL }
uniform int mode;
uniform float exposure;
in vec3 worldNormal;
flat in int probe;
flat in int state;
out vec4 fragColour;
const vec3 STATE_COLOURS[4] = vec3[4]( ${ states } );
vec3 toSrgb( vec3 c ) {
  c = clamp( c, 0.0, 1.0 );
  return mix( 1.055 * pow( c, vec3( 1.0 / 2.4 ) ) - 0.055, 12.92 * c, vec3( lessThanEqual( c, vec3( 0.0031308 ) ) ) );
}
void main() {
  vec3 n = normalize( worldNormal );
  vec3 colour;
  if ( mode == ${ MODE_STATES } ) colour = STATE_COLOURS[ clamp( state, 0, 3 ) ];
  else if ( mode == ${ MODE_VISIBILITY } ) colour = toSrgb( vec3( bakerVisibility( probe, n ) ) );
  else colour = toSrgb( bakerIrradiance( probe, n ) / 3.14159265358979 * exposure );
  fragColour = vec4( colour, 1.0 );
}`,
	} );
}

// Per row of level l, a bit for each finer level that holds a probe at the same place: while that
// level is shown, its sphere is drawn there instead (the value sampling reads at that point).
function finerLevelsHolding( levels, l ) {
	const level = levels[ l ], covered = new Uint8Array( level.rows );
	for ( let r = 0; r < level.rows; ++ r ) {
		const at = probePosition( level, probeOfRow( level, r ) );
		for ( let m = l + 1; m < levels.length; ++ m ) {
			const finer = levels[ m ];
			const ijk = [ 0, 1, 2 ].map( ( a ) => ( at.getComponent( a ) - finer.origin[ a ] ) / finer.spacing );
			if ( ijk.some( ( x, a ) => Math.abs( x - Math.round( x ) ) > 1e-4 || Math.round( x ) < 0 || Math.round( x ) >= finer.dims[ a ] ) ) continue;
			const [ i, j, k ] = ijk.map( Math.round );
			if ( rowOfProbe( finer, i + finer.dims[ 0 ] * ( j + finer.dims[ 1 ] * k ) ) >= 0 ) covered[ r ] |= 1 << m;
		}
	}
	return covered;
}

// One sphere per probe of a level, instance r drawing the level's row r; showLevels() hides those a
// shown finer level draws.
function probeSpheres( volume, l, renderer ) {
	const level = volume.levels[ l ];
	const radius = 0.12 * level.spacing;
	// About half a million triangles in all, whatever the probe count (SwiftShader draws the tests'
	// pages on the CPU); a pixel's normal is interpolated, so a sphere looks round at any count.
	const rows = volume.levels.reduce( ( sum, other ) => sum + other.rows, 0 );
	const segments = 2 * Math.min( 32, Math.max( 6, Math.floor( Math.sqrt( 5e5 / rows ) / 2 ) ) );
	const mesh = new THREE.InstancedMesh( new THREE.SphereGeometry( radius, segments, segments / 2 ), probeMaterial( volume, level, renderer ), level.rows );
	const state = new Float32Array( level.rows );
	for ( let r = 0; r < level.rows; ++ r ) state[ r ] = level.states[ r ];
	mesh.geometry.setAttribute( 'probeState', new THREE.InstancedBufferAttribute( state, 1 ) );
	mesh.userData = { radius, level, shownLevels: - 1 };
	return mesh;
}

// Places the spheres (and arrows) of every level for the levels shown (bit l: level l): a probe a
// shown finer level also holds is drawn at zero size.
function showLevels( meshes, arrows, shownLevels ) {
	const matrix = new THREE.Matrix4(), zero = new THREE.Vector3( 0, 0, 0 ), one = new THREE.Vector3( 1, 1, 1 ), turn = new THREE.Quaternion();
	meshes.forEach( ( mesh, l ) => {
		const { level } = mesh.userData;
		if ( mesh.userData.shownLevels === shownLevels ) return;
		mesh.userData.shownLevels = shownLevels;
		for ( let r = 0; r < level.rows; ++ r ) {
			const hidden = ( level.coveredBy[ r ] & shownLevels ) !== 0;
			mesh.setMatrixAt( r, matrix.compose( probePosition( level, probeOfRow( level, r ) ), turn, hidden ? zero : one ) );
		}
		mesh.instanceMatrix.needsUpdate = true;
		mesh.computeBoundingSphere();
		arrows[ l ].children.forEach( ( arrow ) => { arrow.visible = ( level.coveredBy[ arrow.userData.row ] & shownLevels ) === 0; } );
	} );
}

// Arrows from each relocated probe's grid position to where its light was gathered.
function relocationArrows( level ) {
	const group = new THREE.Group();
	for ( let r = 0; r < level.rows; ++ r ) {
		if ( level.states[ r ] !== 2 ) continue;
		const offset = new THREE.Vector3( ...level.offsets.subarray( 3 * r, 3 * r + 3 ) );
		const length = offset.length();
		if ( ! ( length > 0 ) ) continue;
		const arrow = new THREE.ArrowHelper( offset.clone().normalize(), probePosition( level, probeOfRow( level, r ) ), length, 0xfbbc04, Math.min( 0.3 * length, 0.1 * level.spacing ), Math.min( 0.2 * length, 0.06 * level.spacing ) );
		arrow.userData.row = r;
		group.add( arrow );
	}
	return group;
}

// A slice through the grid across `axis`, textured with the display of E for the chosen normal.
class Slice {
	constructor( volume, axis ) {
		this.volume = volume;
		this.axis = axis;
		const { box } = volume;
		this.inPlane = [ 0, 1, 2 ].filter( ( a ) => a !== axis );
		this.lo = box.lo;
		this.hi = box.hi;
		this.size = this.inPlane.map( ( a ) => Math.min( 256, Math.max( 2, 4 * Math.round( ( box.hi[ a ] - box.lo[ a ] ) / box.spacing ) + 1 ) ) );
		const pixels = new Uint8Array( 4 * this.size[ 0 ] * this.size[ 1 ] );
		this.texture = new THREE.DataTexture( pixels, this.size[ 0 ], this.size[ 1 ], THREE.RGBAFormat );
		this.texture.colorSpace = THREE.SRGBColorSpace;
		this.texture.magFilter = THREE.LinearFilter;
		const geometry = new THREE.BufferGeometry();
		geometry.setAttribute( 'position', new THREE.BufferAttribute( new Float32Array( 12 ), 3 ) );
		geometry.setAttribute( 'uv', new THREE.BufferAttribute( new Float32Array( [ 0, 0, 1, 0, 1, 1, 0, 1 ] ), 2 ) );
		geometry.setIndex( [ 0, 1, 2, 0, 2, 3 ] );
		this.mesh = new THREE.Mesh( geometry, new THREE.MeshBasicMaterial( { map: this.texture, side: THREE.DoubleSide, toneMapped: false } ) );
	}

	update( fraction, normal, exposure, visibilityMode, leakAware ) {
		const [ u, v ] = this.inPlane, a = this.axis;
		const at = this.lo[ a ] + fraction * ( this.hi[ a ] - this.lo[ a ] );
		const corner = ( su, sv ) => { const p = [ 0, 0, 0 ]; p[ a ] = at; p[ u ] = su ? this.hi[ u ] : this.lo[ u ]; p[ v ] = sv ? this.hi[ v ] : this.lo[ v ]; return p; };
		const positions = this.mesh.geometry.attributes.position;
		[ corner( 0, 0 ), corner( 1, 0 ), corner( 1, 1 ), corner( 0, 1 ) ].forEach( ( p, i ) => positions.setXYZ( i, ...p ) );
		positions.needsUpdate = true;
		this.mesh.geometry.computeBoundingSphere();
		const [ w, h ] = this.size, pixels = this.texture.image.data;
		for ( let j = 0; j < h; ++ j ) for ( let i = 0; i < w; ++ i ) {
			const p = [ 0, 0, 0 ];
			p[ a ] = at;
			p[ u ] = this.lo[ u ] + ( i / ( w - 1 ) ) * ( this.hi[ u ] - this.lo[ u ] );
			p[ v ] = this.lo[ v ] + ( j / ( h - 1 ) ) * ( this.hi[ v ] - this.lo[ v ] );
			const s = sampleAt( this.volume, p, normal, leakAware );
			const shown = visibilityMode && s.visibility !== null ? [ s.visibility, s.visibility, s.visibility ] : s.irradiance.map( ( e ) => e / Math.PI * exposure );
			const at4 = 4 * ( j * w + i );
			for ( let c = 0; c < 3; ++ c ) pixels[ at4 + c ] = Math.round( 255 * linearToSrgb( shown[ c ] ) );
			pixels[ at4 + 3 ] = 255;
		}
		this.texture.needsUpdate = true;
	}
}

// An exposure that puts the brighter probes (95th percentile of E/π over the six axes) at 0.8.
function initialExposure( volume ) {
	const values = [];
	const rows = volume.levels.reduce( ( sum, level ) => sum + level.rows, 0 );
	const step = Math.max( 1, Math.floor( rows / 4096 ) );
	for ( const level of volume.levels ) {
		for ( let r = 0; r < level.rows; r += step ) {
			if ( level.states[ r ] === 0 ) continue;
			for ( const n of Object.values( AXES ) ) values.push( Math.max( ...volume.decoder.irradiance( level.coefficients, n, r * volume.decoder.coefficientsPerProbe ) ) / Math.PI );
		}
	}
	values.sort( ( x, y ) => x - y );
	const bright = values.length ? values[ Math.floor( 0.95 * ( values.length - 1 ) ) ] : 1;
	return bright > 0 ? Math.round( 10 * Math.log2( 0.8 / bright ) ) / 10 : 0;
}

function summaryOf( volume ) {
	const { info, levels } = volume;
	const count = ( state ) => levels.reduce( ( sum, level ) => sum + level.states.filter( ( s ) => s === state ).length, 0 );
	const grid = levels.length === 1 ? `${ info.dims.join( ' × ' ) } probes, spacing ${ info.spacing } m` :
		`${ levels.length } levels, spacing ${ levels[ 0 ].spacing.toPrecision( 4 ) } to ${ levels[ levels.length - 1 ].spacing.toPrecision( 4 ) } m, ${ levels.reduce( ( sum, level ) => sum + level.rows, 0 ) } probes held`;
	return `${ grid }; ${ count( 2 ) } relocated, ${ count( 0 ) } filled` + ( levels.length > 1 ? `, ${ count( 3 ) } interpolated at level borders` : '' ) +
		( info.scene ? '' : '; no scene (baker view --gltf)' );
}

async function loadScene( url, scene ) {
	if ( ! url ) return null;
	const gltf = await new GLTFLoader().loadAsync( url );
	scene.add( gltf.scene );
	return gltf.scene;
}

async function main() {
	const volume = await loadVolume();
	const { info } = volume;
	const canvas = $( 'view' );
	const renderer = new THREE.WebGLRenderer( { canvas, antialias: true, preserveDrawingBuffer: true } );
	renderer.setPixelRatio( window.devicePixelRatio );
	renderer.setSize( canvas.clientWidth, canvas.clientHeight, false );
	renderer.toneMapping = THREE.NoToneMapping;
	const scene = new THREE.Scene();
	scene.background = new THREE.Color( 0x202124 );
	scene.add( new THREE.HemisphereLight( 0xffffff, 0x444444, 1.5 ) );
	const sun = new THREE.DirectionalLight( 0xffffff, 1.0 );
	sun.position.set( 1, 2, 1.5 );
	scene.add( sun );

	const { box } = volume;
	const centre = new THREE.Vector3( ...box.lo.map( ( lo, a ) => 0.5 * ( lo + box.hi[ a ] ) ) );
	const extent = Math.max( ...box.hi.map( ( hi, a ) => hi - box.lo[ a ] ) ) + box.spacing;
	const camera = new THREE.PerspectiveCamera( 50, canvas.clientWidth / canvas.clientHeight, extent * 1e-3, extent * 20 );
	camera.position.copy( centre ).add( new THREE.Vector3( 0.9, 0.7, 1.2 ).multiplyScalar( extent ) );
	const controls = new OrbitControls( camera, canvas );
	controls.target.copy( centre );
	controls.update();

	// Drawn when something changes rather than every frame: the probes of a large volume are
	// millions of triangles.
	function render() {
		renderer.render( scene, camera );
	}
	let frameRequested = false;
	function requestRender() {
		if ( frameRequested ) return;
		frameRequested = true;
		requestAnimationFrame( () => { frameRequested = false; render(); } );
	}
	controls.addEventListener( 'change', requestRender );

	const probes = volume.levels.map( ( _, l ) => probeSpheres( volume, l, renderer ) );
	const arrows = volume.levels.map( ( level ) => relocationArrows( level ) );
	[ ...probes, ...arrows ].forEach( ( o ) => scene.add( o ) );
	const slices = [ 0, 1, 2 ].map( ( axis ) => new Slice( volume, axis ) );
	slices.forEach( ( s ) => scene.add( s.mesh ) );
	const gltfScene = await loadScene( info.scene, scene );

	$( 'title' ).textContent = `${ info.volume }: ${ info.basis }`;
	$( 'summary' ).textContent = summaryOf( volume );
	$( 'levels' ).innerHTML = volume.levels.map( ( l ) => `<label><input type="checkbox" class="level" id="level-${ l.level }" checked> level ${ l.level } (spacing ${ l.spacing.toPrecision( 4 ) } m, ${ l.rows } probes)</label>` ).join( '' );
	for ( const name of Object.keys( AXES ) ) $( 'slice-normal' ).add( new Option( name, name, name === '+Y', name === '+Y' ) );
	$( 'exposure' ).value = initialExposure( volume );
	if ( info.visibility_per_probe === 0 ) $( 'show-visibility' ).disabled = true;
	if ( ! info.distance_map ) {
		$( 'leak-aware' ).disabled = true;
		$( 'leak-aware' ).parentElement.title = 'this volume holds no distance maps (adaptive volumes, the Bevy and three.js exports, bakes with --distance-map 0)';
	}

	const settings = () => ( {
		exposure: Math.pow( 2, Number( $( 'exposure' ).value ) ),
		mode: $( 'show-states' ).checked ? MODE_STATES : $( 'show-visibility' ).checked ? MODE_VISIBILITY : MODE_IRRADIANCE,
		leakAware: $( 'leak-aware' ).checked && ! $( 'leak-aware' ).disabled,
	} );
	function refresh() {
		const { exposure, mode, leakAware } = settings();
		const shownLevels = probes.reduce( ( bits, _, l ) => bits | ( $( `level-${ l }` ).checked ? 1 << l : 0 ), 0 );
		showLevels( probes, arrows, shownLevels );
		probes.forEach( ( mesh, l ) => {
			mesh.material.uniforms.exposure.value = exposure;
			mesh.material.uniforms.mode.value = mode;
			mesh.visible = $( 'show-probes' ).checked && ( shownLevels >> l & 1 ) === 1;
			arrows[ l ].visible = $( 'show-offsets' ).checked && ( shownLevels >> l & 1 ) === 1;
		} );
		if ( gltfScene ) gltfScene.visible = $( 'show-scene' ).checked;
		const visibilityMode = mode === MODE_VISIBILITY;
		slices.forEach( ( s, a ) => {
			s.mesh.visible = $( `slice-${ 'xyz'[ a ] }` ).checked;
			if ( s.mesh.visible ) s.update( Number( $( `slice-${ 'xyz'[ a ] }-at` ).value ) / 1000, AXES[ $( 'slice-normal' ).value ], exposure, visibilityMode, leakAware );
		} );
		$( 'exposure-value' ).textContent = `${ Number( $( 'exposure' ).value ).toFixed( 1 ) } stops (×${ exposure.toPrecision( 3 ) })`;
		drawColourBar( exposure, visibilityMode );
		requestRender();
	}
	function drawColourBar( exposure, visibilityMode ) {
		const bar = $( 'colourbar' ), context = bar.getContext( '2d' );
		for ( let x = 0; x < bar.width; ++ x ) {
			const g = Math.round( 255 * linearToSrgb( x / ( bar.width - 1 ) ) );
			context.fillStyle = `rgb(${ g },${ g },${ g })`;
			context.fillRect( x, 0, 1, bar.height );
		}
		const top = visibilityMode ? 1 : Math.PI / exposure;
		$( 'ticks' ).innerHTML = [ 0, 0.25, 0.5, 0.75, 1 ].map( ( f ) => `<span>${ ( f * top ).toPrecision( 3 ) }</span>` ).join( '' );
		$( 'units' ).textContent = visibilityMode ? 'sky visibility V(n): 1 under open sky' : `E(n): ${ info.units }; white where E/π · exposure reaches 1`;
	}
	// Slices are decoded on the CPU: at most once a frame however fast a slider moves.
	let pending = false;
	const scheduleRefresh = () => {
		if ( pending ) return;
		pending = true;
		requestAnimationFrame( () => { pending = false; refresh(); } );
	};
	document.querySelectorAll( '#panel input, #panel select' ).forEach( ( e ) => e.addEventListener( 'input', scheduleRefresh ) );
	refresh();

	// A click (not a drag) prints the point and its irradiance for the six axis normals.
	const raycaster = new THREE.Raycaster();
	let down = null;
	canvas.addEventListener( 'pointerdown', ( e ) => { down = [ e.clientX, e.clientY ]; } );
	canvas.addEventListener( 'pointerup', ( e ) => {
		if ( ! down || Math.hypot( e.clientX - down[ 0 ], e.clientY - down[ 1 ] ) > 4 ) return;
		const rect = canvas.getBoundingClientRect();
		raycaster.setFromCamera( new THREE.Vector2( ( e.clientX - rect.left ) / rect.width * 2 - 1, - ( ( e.clientY - rect.top ) / rect.height ) * 2 + 1 ), camera );
		const targets = [ ...probes, ...slices.map( ( s ) => s.mesh ), ...( gltfScene ? [ gltfScene ] : [] ) ].filter( ( o ) => o.visible );
		const hit = raycaster.intersectObjects( targets, true )[ 0 ];
		if ( hit ) pick( hit.point.toArray() );
	} );
	function pick( position ) {
		const { leakAware } = settings();
		const lines = [ `position (${ position.map( ( x ) => x.toFixed( 4 ) ).join( ', ' ) })${ leakAware ? ', leak-aware' : '' }` ];
		const result = { position, leakAware, irradiance: {} };
		for ( const [ name, n ] of Object.entries( AXES ) ) {
			const s = sampleAt( volume, position, n, leakAware );
			result.irradiance[ name ] = s.irradiance;
			lines.push( `${ name }  E = (${ s.irradiance.map( ( x ) => x.toPrecision( 6 ) ).join( ', ' ) })` );
		}
		$( 'picked' ).textContent = lines.join( '\n' );
		console.log( JSON.stringify( result ) );
		return result;
	}

	window.addEventListener( 'resize', () => {
		renderer.setSize( canvas.clientWidth, canvas.clientHeight, false );
		camera.aspect = canvas.clientWidth / canvas.clientHeight;
		camera.updateProjectionMatrix();
		requestRender();
	} );

	// For tests and scripts: the colours of the four pixels around the centre of the sphere of
	// probe (i, j, k) of `level` seen from `towards` (its normal there; the centre is their common
	// corner, so their mean is the colour there to second order), with only that level's probes
	// drawn; and pick() as a click does.
	window.viewer = {
		info,
		pick,
		resetExposure() {
			$( 'exposure' ).value = initialExposure( volume );
			refresh();
		},
		setOption( id, value ) {
			const e = $( id );
			if ( e.type === 'checkbox' ) e.checked = value;
			else e.value = String( value );
			refresh();
		},
		captureProbe( ijk, towards, l = 0 ) {
			const level = volume.levels[ l ], p = ijk[ 0 ] + level.dims[ 0 ] * ( ijk[ 1 ] + level.dims[ 1 ] * ijk[ 2 ] );
			if ( rowOfProbe( level, p ) < 0 ) throw new Error( `level ${ l } holds no probe ${ ijk }` );
			const at = probePosition( level, p );
			const n = new THREE.Vector3( ...towards ).normalize();
			const saved = { position: camera.position.clone(), target: controls.target.clone() };
			const hidden = [ ...probes.filter( ( _, m ) => m !== l ), ...arrows, ...slices.map( ( s ) => s.mesh ), ...( gltfScene ? [ gltfScene ] : [] ) ].filter( ( o ) => o.visible );
			hidden.forEach( ( o ) => { o.visible = false; } );
			camera.position.copy( at ).addScaledVector( n, 6 * probes[ l ].userData.radius );
			camera.lookAt( at );
			render();
			const gl = renderer.getContext(), block = new Uint8Array( 16 );
			gl.readPixels( gl.drawingBufferWidth / 2 - 1, gl.drawingBufferHeight / 2 - 1, 2, 2, gl.RGBA, gl.UNSIGNED_BYTE, block );
			hidden.forEach( ( o ) => { o.visible = true; } );
			camera.position.copy( saved.position );
			controls.target.copy( saved.target );
			camera.lookAt( saved.target );
			requestRender();
			const pixels = [ 0, 1, 2, 3 ].map( ( i ) => Array.from( block.slice( 4 * i, 4 * i + 3 ) ) );
			return { pixels, position: at.toArray(), normal: n.toArray(), exposure: settings().exposure };
		},
	};
	window.viewerReady = true;
}

main().catch( ( error ) => {
	console.error( error );
	$( 'summary' ).textContent = `cannot show the volume: ${ error.message }`;
} );
