// baker_irradiance_webgl.js — the reference decoder (decoders/baker_irradiance.h) as GLSL ES 3.00
// for WebGL 2, every basis, with what a page needs to feed it: the probes' values in a float
// texture and the basis's parameters as uniforms, both from a BasisDecoder of
// baker_irradiance.js.
//
//   const decoder = new BasisDecoder( basis, sharpness );
//   const texture = probeTexture( coefficients, visibility, decoder );  // { data, width, height, stride }
//   fragment shader: BAKER_IRRADIANCE_GLSL, then bakerIrradiance( probe, n ), bakerVisibility( probe, n )
//   uniforms: bakerUniforms( decoder, texture ): { name: { type, value } } as declared in the GLSL
//
// Adaptive volumes (several levels, each holding some bricks of 8³ probes):
//   const pool = adaptiveTextures( levels, decoder );   // { probes, indirection, uniforms }
//   fragment shader: BAKER_IRRADIANCE_GLSL, then await adaptiveGlsl(), then
//   bakerAdaptiveIrradiance( position, n ), bakerAdaptiveVisibility( position, n )
//   uniforms: bakerUniforms( decoder, pool.probes ) and pool.uniforms; bind pool.indirection as an
//   R32UI 3D texture to bakerIndirection, filters NEAREST and no mipmaps (an incomplete texture
//   reads 0); the fragment shader needs precision highp int
import { icosahedronVertex } from './baker_irradiance.js';

// Levels an adaptive volume holds at most (shaders/baker_adaptive.glsl's BAKER_MAX_LEVELS).
export const MAX_LEVELS = 4;
const BRICK_PROBES = 512;

// Texels per row of the probe texture: rows stay within every WebGL 2 implementation's limits.
export const PROBE_TEXTURE_WIDTH = 1024;
export const MAX_LOBES = 64;
const MAX_SH_ORDER = 8; // what a volume's sh-lN bases reach

const KINDS = { 'sh': 0, 'icosahedron-linear': 1, 'icosahedron-lobes': 2, 'icosahedron-bezier': 3, 'cube-lobes': 4, 'spherical-gaussians': 5 };

function glslVec3( v ) { return `vec3(${ v.map( ( x ) => x.toPrecision( 17 ) ).join( ', ' ) })`; }

// The values of every probe for the texture: per probe its coefficients, then its visibility
// (channel 0's functions), stride floats in all, padded to whole RGBA texels.
export function probeTexture( coefficients, visibility, decoder, probeCount ) {
	const perProbe = decoder.coefficientsPerProbe, visibilityCount = visibility ? decoder.coefficientCount( 0 ) : 0;
	const stride = perProbe + visibilityCount;
	const texels = Math.ceil( probeCount * stride / 4 );
	const width = PROBE_TEXTURE_WIDTH, height = Math.max( 1, Math.ceil( texels / width ) );
	const data = new Float32Array( width * height * 4 );
	for ( let p = 0; p < probeCount; ++ p ) {
		data.set( coefficients.subarray( p * perProbe, ( p + 1 ) * perProbe ), p * stride );
		if ( visibilityCount ) data.set( visibility.subarray( p * visibilityCount, ( p + 1 ) * visibilityCount ), p * stride + perProbe );
	}
	return { data, width, height, stride };
}

// Uniform values by name, each { type: 'int' | 'float' | 'vec3[]', value }; three.js takes
// { value } alone. bakerProbes is the texture itself, which the caller binds.
function setUniforms( prefix, set ) {
	const axes = new Float32Array( 3 * MAX_LOBES );
	set.axes.forEach( ( a, i ) => axes.set( a, 3 * i ) );
	const int = ( value ) => ( { type: 'int', value } ), float = ( value ) => ( { type: 'float', value } );
	return {
		[ `${ prefix }Kind` ]: int( KINDS[ set.kind ] ),
		[ `${ prefix }ShOrder` ]: int( set.shOrder ),
		[ `${ prefix }Spherical` ]: int( set.spherical ? 1 : 0 ),
		[ `${ prefix }Cos2` ]: float( set.cos2 ),
		[ `${ prefix }Cos4` ]: float( set.cos4 ),
		[ `${ prefix }Sharpness` ]: float( set.sharpness ),
		[ `${ prefix }LobeCount` ]: int( set.axes.length ),
		[ `${ prefix }Axes` ]: { type: 'vec3[]', value: axes },
		[ `${ prefix }Count` ]: int( set.count ),
	};
}

export function bakerUniforms( decoder, texture ) {
	if ( decoder.primary.kind === 'sh' && decoder.primary.shOrder > MAX_SH_ORDER ) throw new Error( `sh-l${ decoder.primary.shOrder }: the WebGL decoder reaches sh-l${ MAX_SH_ORDER }` );
	return {
		...setUniforms( 'bakerPrimary', decoder.primary ),
		...setUniforms( 'bakerChroma', decoder.ycocg ? decoder.chroma : decoder.primary ),
		bakerYCoCg: { type: 'int', value: decoder.ycocg ? 1 : 0 },
		bakerStride: { type: 'int', value: texture.stride },
		bakerVisibilityOffset: { type: 'int', value: decoder.coefficientsPerProbe },
	};
}

const vertices = Array.from( { length: 12 }, ( _, i ) => glslVec3( icosahedronVertex( i ) ) ).join( ',\n  ' );

function setDeclarations( prefix ) {
	return `uniform int ${ prefix }Kind, ${ prefix }ShOrder, ${ prefix }Spherical, ${ prefix }LobeCount, ${ prefix }Count;
uniform float ${ prefix }Cos2, ${ prefix }Cos4, ${ prefix }Sharpness;
uniform vec3 ${ prefix }Axes[${ MAX_LOBES }];`;
}

// Σ values·f_i(d) of up to three arrays of one function set (`arrays` channels sharing it).
function expandFunction( set ) {
	const u = ( name ) => `baker${ set }${ name }`;
	return /* glsl */ `
vec3 bakerExpand${ set }( int probe, int base, int arrays, vec3 d ) {
  int count = ${ u( 'Count' ) };
  vec3 sums = vec3( 0.0 );
  if ( ${ u( 'Kind' ) } == 0 ) return bakerSphericalHarmonics( ${ u( 'ShOrder' ) }, probe, base, count, arrays, d );
  if ( ${ u( 'Kind' ) } == 1 || ${ u( 'Kind' ) } == 3 ) {
    ivec3 vertex;
    vec3 spherical;
    bakerLocate( d, vertex, spherical );
    bool sphericalBarycentrics = ${ u( 'Spherical' ) } != 0;
    vec3 b = sphericalBarycentrics ? spherical : spherical / ( spherical.x + spherical.y + spherical.z );
    for ( int k = 0; k < 3; ++ k ) {
      if ( k >= arrays ) break;
      if ( ${ u( 'Kind' ) } == 3 ) {
        sums[ k ] = bakerBezier( vertex, b, sphericalBarycentrics, probe, base + k * count );
        continue;
      }
      for ( int c = 0; c < 3; ++ c ) sums[ k ] += b[ c ] * bakerValue( probe, base + k * count + vertex[ c ] );
    }
    return sums;
  }
  if ( ${ u( 'Kind' ) } == 2 ) {
    for ( int i = 0; i < 12; ++ i ) {
      float c = dot( BAKER_VERTEX[ i ], d );
      if ( c <= 0.0 ) continue;
      float lobe = c * c * ( ${ u( 'Cos2' ) } + ${ u( 'Cos4' ) } * c * c );
      for ( int k = 0; k < 3; ++ k ) if ( k < arrays ) sums[ k ] += lobe * bakerValue( probe, base + k * count + i );
    }
    return sums;
  }
  if ( ${ u( 'Kind' ) } == 4 ) {
    for ( int a = 0; a < 3; ++ a ) {
      int lobe = 2 * a + ( d[ a ] < 0.0 ? 1 : 0 );
      for ( int k = 0; k < 3; ++ k ) if ( k < arrays ) sums[ k ] += d[ a ] * d[ a ] * bakerValue( probe, base + k * count + lobe );
    }
    return sums;
  }
  for ( int i = 0; i < ${ MAX_LOBES }; ++ i ) {
    if ( i >= ${ u( 'LobeCount' ) } ) break;
    float lobe = exp( ${ u( 'Sharpness' ) } * ( dot( ${ u( 'Axes' ) }[ i ], d ) - 1.0 ) );
    for ( int k = 0; k < 3; ++ k ) if ( k < arrays ) sums[ k ] += lobe * bakerValue( probe, base + k * count + i );
  }
  return sums;
}`;
}

export const BAKER_IRRADIANCE_GLSL = /* glsl */ `
// The decoders of decoders/baker_irradiance.h, evaluated per pixel (see baker_irradiance_webgl.js).
uniform highp sampler2D bakerProbes;
uniform int bakerStride, bakerVisibilityOffset, bakerYCoCg;
${ setDeclarations( 'bakerPrimary' ) }
${ setDeclarations( 'bakerChroma' ) }

const float BAKER_PHI = 0.61803398874989484820;
const vec3 BAKER_VERTEX[12] = vec3[12](
  ${ vertices });

float bakerValue( int probe, int index ) {
  int f = probe * bakerStride + index;
  int t = f / 4;
  vec4 texel = texelFetch( bakerProbes, ivec2( t % ${ PROBE_TEXTURE_WIDTH }, t / ${ PROBE_TEXTURE_WIDTH } ), 0 );
  return texel[ f - 4 * t ];
}

vec3 bakerTangent( int i ) { return i < 4 ? vec3( 0, 0, 1 ) : i < 8 ? vec3( 1, 0, 0 ) : vec3( 0, 1, 0 ); }

// The icosahedron triangle holding d: its vertices and d's spherical barycentrics.
void bakerLocate( vec3 d, out ivec3 vertex, out vec3 spherical ) {
  int sx = d.x < 0.0 ? 1 : 0, sy = d.y < 0.0 ? 1 : 0, sz = d.z < 0.0 ? 1 : 0;
  vec3 a = abs( d );
  float phi2 = 1.0 - BAKER_PHI;
  int va = sx + 2 * sy, vb = 4 + sy + 2 * sz, vc = 8 + sx + 2 * sz;
  if ( phi2 * a.x - BAKER_PHI * a.y + a.z <= 0.0 ) vc = vb ^ 2;
  else if ( - BAKER_PHI * a.x + a.y + phi2 * a.z <= 0.0 ) vb = va ^ 2;
  else if ( a.x + phi2 * a.y - BAKER_PHI * a.z <= 0.0 ) va = vc ^ 1;
  vertex = ivec3( va, vb, vc );
  vec3 v0 = BAKER_VERTEX[ va ], v1 = BAKER_VERTEX[ vb ], v2 = BAKER_VERTEX[ vc ];
  vec3 r0 = cross( v1, v2 ), r1 = cross( v2, v0 ), r2 = cross( v0, v1 );
  float determinant = dot( v0, r0 );
  spherical = vec3( dot( d, r0 ), dot( d, r1 ), dot( d, r2 ) ) / determinant;
}

// Real SH without the Condon–Shortley phase, polar axis z: the header's recurrences.
vec3 bakerSphericalHarmonics( int order, int probe, int base, int count, int arrays, vec3 d ) {
  vec3 sums = vec3( 0.0 );
  float re = 1.0, im = 0.0, diagonal = sqrt( 1.0 / ( 4.0 * 3.14159265358979 ) );
  for ( int m = 0; m <= ${ MAX_SH_ORDER }; ++ m ) {
    if ( m > order ) break;
    if ( m > 0 ) {
      float nextRe = re * d.x - im * d.y;
      im = re * d.y + im * d.x;
      re = nextRe;
      diagonal *= sqrt( float( 2 * m + 1 ) / float( 2 * m ) );
    }
    float previous = 0.0, current = diagonal;
    for ( int l = m; l <= ${ MAX_SH_ORDER }; ++ l ) {
      if ( l > order ) break;
      if ( l > m ) {
        float fl = float( l ), fm = float( m );
        float a = sqrt( ( 4.0 * fl * fl - 1.0 ) / ( fl * fl - fm * fm ) );
        float b = sqrt( ( ( fl - 1.0 ) * ( fl - 1.0 ) - fm * fm ) / ( 4.0 * ( fl - 1.0 ) * ( fl - 1.0 ) - 1.0 ) );
        float next = a * ( d.z * current - b * previous );
        previous = current;
        current = next;
      }
      int centre = l * l + l;
      for ( int k = 0; k < 3; ++ k ) {
        if ( k >= arrays ) break;
        int c = base + k * count;
        if ( m == 0 ) sums[ k ] += current * bakerValue( probe, c + centre );
        else sums[ k ] += 1.4142135623730951 * current * ( re * bakerValue( probe, c + centre + m ) + im * bakerValue( probe, c + centre - m ) );
      }
    }
  }
  return sums;
}

// The cubic Bézier patch of the triangle (Ambient Dice §2.3.1), from 36 values at base.
float bakerBezier( ivec3 vertex, vec3 b, bool spherical, int probe, int base ) {
  float root5 = sqrt( 5.0 );
  float vertexFactor = spherical ? 1.0 / root5 : 1.0;
  float a0 = spherical ? ( root5 - 5.0 ) / 40.0 : - 0.25;
  float a1 = spherical ? ( 11.0 * root5 - 15.0 ) / 40.0 : 0.25;
  float a2 = spherical ? root5 / 10.0 : 0.5;
  float alpha = 0.5 * sqrt( ( 5.0 + root5 ) / 2.0 );
  float corner[3];
  vec3 gradient[3];
  for ( int k = 0; k < 3; ++ k ) {
    int v = vertex[ k ], at = base + 3 * v;
    corner[ k ] = bakerValue( probe, at );
    vec3 t = bakerTangent( v );
    gradient[ k ] = bakerValue( probe, at + 1 ) * t + bakerValue( probe, at + 2 ) * cross( BAKER_VERTEX[ v ], t );
  }
  float edge[9];
  for ( int k = 0; k < 3; ++ k )
    for ( int m = 0; m < 3; ++ m )
      edge[ 3 * k + m ] = vertexFactor * corner[ k ] + ( root5 / 2.0 ) * dot( BAKER_VERTEX[ vertex[ m ] ], gradient[ k ] ) / ( 3.0 * alpha );
  float value = 0.0;
  for ( int k = 0; k < 3; ++ k ) {
    value += b[ k ] * b[ k ] * b[ k ] * corner[ k ];
    for ( int m = 0; m < 3; ++ m )
      if ( m != k ) value += 3.0 * b[ k ] * b[ k ] * b[ m ] * edge[ 3 * k + m ];
  }
  vec3 p = max( b, vec3( 0.0 ) );
  float weightSum = p.y * p.z + p.x * p.z + p.x * p.y;
  if ( weightSum <= 0.0 ) return value;
  float centre = 0.0;
  for ( int j = 0; j < 3; ++ j ) {
    int k = ( j + 1 ) % 3, m = ( j + 2 ) % 3;
    float w = p[ k ] * p[ m ] / weightSum;
    centre += w * ( a0 * ( corner[ k ] + corner[ m ] ) + a1 * ( edge[ 3 * k + m ] + edge[ 3 * m + k ] ) + a2 * ( edge[ 3 * k + j ] + edge[ 3 * m + j ] ) );
  }
  return value + 6.0 * b.x * b.y * b.z * centre;
}

${ expandFunction( 'Primary' ) }
${ expandFunction( 'Chroma' ) }

// RGB irradiance E(n) of probe \`probe\` at unit normal n.
vec3 bakerIrradiance( int probe, vec3 n ) {
  if ( bakerYCoCg == 0 ) return bakerExpandPrimary( probe, 0, 3, n );
  float y = bakerExpandPrimary( probe, 0, 1, n ).x;
  vec3 chroma = bakerExpandChroma( probe, bakerPrimaryCount, 2, n );
  return vec3( y + chroma.x - chroma.y, y + chroma.y, y - chroma.x - chroma.y );
}

// Sky visibility of probe \`probe\` at unit normal n (channel 0's functions).
float bakerVisibility( int probe, vec3 n ) { return bakerExpandPrimary( probe, bakerVisibilityOffset, 1, n ).x; }
`;

// The textures of an adaptive volume, from its levels (coarsest first), each { origin, spacing,
// dims, bricks, masks, coefficients, visibility }: `bricks` the held bricks' indices bx + Bx·(by + By·bz)
// in increasing order (the EXR atlas's "bricks"), `masks` the sub-bricks held of each (the atlas's
// "masks"; absent or null when every brick is whole), `coefficients` and `visibility` (or null) per
// brick in that order, per probe i + 8·(j + 8·k) of the brick (the atlas slot's probes).
// - probes: probeTexture of the pool, the levels' bricks one after the other, 512 probes each;
// - indirection: { data: Uint32Array, width, height, depth }, texel (bx, by, brickZ + bz) = 1 +
//   the pool slot of the level's brick + its sub-brick mask · 2^24, 0 where it holds none; levels
//   stacked along z;
// - uniforms: the levels' grids for the GLSL, { name: { type, value } }.
// maxTextureSize: gl.getParameter( gl.MAX_TEXTURE_SIZE ), to refuse a pool taller than the GPU takes.
export function adaptiveTextures( levels, decoder, maxTextureSize = Infinity ) {
	if ( levels.length < 1 || levels.length > MAX_LEVELS ) throw new Error( `${ levels.length } levels: an adaptive volume has 1 to ${ MAX_LEVELS }` );
	const brickCounts = levels.map( ( l ) => l.dims.map( ( d ) => Math.ceil( d / 8 ) ) );
	const width = Math.max( ...brickCounts.map( ( b ) => b[ 0 ] ) ), height = Math.max( ...brickCounts.map( ( b ) => b[ 1 ] ) );
	const depth = brickCounts.reduce( ( sum, b ) => sum + b[ 2 ], 0 );
	const indirection = new Uint32Array( width * height * depth );
	const slots = levels.reduce( ( sum, l ) => sum + l.bricks.length, 0 );
	if ( slots > 0xFFFFFF ) throw new Error( `${ slots } bricks: the indirection texture's 24 bits of slot hold at most ${ 0xFFFFFF }` );
	const perProbe = decoder.coefficientsPerProbe, visibilityCount = decoder.coefficientCount( 0 );
	const hasVisibility = levels.every( ( l ) => l.visibility );
	const coefficients = new Float32Array( slots * BRICK_PROBES * perProbe );
	const visibility = hasVisibility ? new Float32Array( slots * BRICK_PROBES * visibilityCount ) : null;
	const origin = new Float32Array( 3 * MAX_LEVELS ), spacing = new Float32Array( MAX_LEVELS );
	const dims = new Int32Array( 3 * MAX_LEVELS ), brickZ = new Int32Array( MAX_LEVELS );
	let slot = 0, z = 0;
	levels.forEach( ( level, l ) => {
		const [ bx, by, bz ] = brickCounts[ l ];
		if ( level.coefficients.length !== level.bricks.length * BRICK_PROBES * perProbe ) throw new Error( `level ${ l }: ${ level.coefficients.length } coefficients for ${ level.bricks.length } bricks of ${ BRICK_PROBES } probes × ${ perProbe }` );
		if ( visibility && level.visibility.length !== level.bricks.length * BRICK_PROBES * visibilityCount ) throw new Error( `level ${ l }: ${ level.visibility.length } visibility values for ${ level.bricks.length } bricks of ${ BRICK_PROBES } probes × ${ visibilityCount }` );
		coefficients.set( level.coefficients, slot * BRICK_PROBES * perProbe );
		if ( visibility ) visibility.set( level.visibility, slot * BRICK_PROBES * visibilityCount );
		level.bricks.forEach( ( b, s ) => {
			if ( ! ( b >= 0 && b < bx * by * bz ) || ( s > 0 && b <= level.bricks[ s - 1 ] ) ) throw new Error( `level ${ l }: brick ${ b } out of range or order` );
			const x = b % bx, y = Math.floor( b / bx ) % by, k = Math.floor( b / ( bx * by ) );
			const mask = level.masks ? level.masks[ s ] : 0xFF;
			if ( ! ( mask >= 1 && mask <= 0xFF ) ) throw new Error( `level ${ l }: brick ${ b } has sub-brick mask ${ mask }` );
			indirection[ x + width * ( y + height * ( z + k ) ) ] = ( ( mask << 24 ) >>> 0 ) + slot + s + 1;
		} );
		origin.set( level.origin, 3 * l );
		spacing[ l ] = level.spacing;
		dims.set( level.dims, 3 * l );
		brickZ[ l ] = z;
		slot += level.bricks.length;
		z += bz;
	} );
	const probes = probeTexture( coefficients, visibility, decoder, slots * BRICK_PROBES );
	if ( probes.height > maxTextureSize || Math.max( width, height, depth ) > maxTextureSize ) throw new Error( `the pool needs ${ probes.height } rows and the indirection ${ width } × ${ height } × ${ depth } texels, beyond this GPU's ${ maxTextureSize }` );
	return {
		probes,
		indirection: { data: indirection, width, height, depth },
		uniforms: {
			bakerLevelCount: { type: 'int', value: levels.length },
			bakerLevelOrigin: { type: 'vec3[]', value: origin },
			bakerLevelSpacing: { type: 'float[]', value: spacing },
			bakerLevelDims: { type: 'ivec3[]', value: dims },
			bakerLevelBrickZ: { type: 'int[]', value: brickZ },
		},
	};
}

// Reads the pool through shaders/baker_adaptive.glsl's corners: each corner's probe decoded and
// weighted (decoding is linear, so this equals decoding the blended probe).
export const BAKER_ADAPTIVE_WEBGL_GLSL = /* glsl */ `
uniform highp usampler3D bakerIndirection;
uniform int bakerLevelCount;
uniform vec3 bakerLevelOrigin[BAKER_MAX_LEVELS];
uniform float bakerLevelSpacing[BAKER_MAX_LEVELS];
uniform ivec3 bakerLevelDims[BAKER_MAX_LEVELS];
uniform int bakerLevelBrickZ[BAKER_MAX_LEVELS];

BakerCorners bakerAdaptiveCornersAt( vec3 position ) {
  return bakerAdaptiveCorners( position, bakerIndirection, bakerLevelCount, bakerLevelOrigin, bakerLevelSpacing, bakerLevelDims, bakerLevelBrickZ );
}
int bakerPoolProbe( BakerCorners corners, int c ) {
  ivec3 p = corners.local[ c ];
  return ${ BRICK_PROBES } * corners.slot[ c ] + p.x + 8 * ( p.y + 8 * p.z );
}
vec3 bakerAdaptiveIrradiance( vec3 position, vec3 n ) {
  BakerCorners corners = bakerAdaptiveCornersAt( position );
  vec3 e = vec3( 0.0 );
  for ( int c = 0; c < 8; ++ c ) if ( corners.weight[ c ] != 0.0 ) e += corners.weight[ c ] * bakerIrradiance( bakerPoolProbe( corners, c ), n );
  return e;
}
float bakerAdaptiveVisibility( vec3 position, vec3 n ) {
  BakerCorners corners = bakerAdaptiveCornersAt( position );
  float v = 0.0;
  for ( int c = 0; c < 8; ++ c ) if ( corners.weight[ c ] != 0.0 ) v += corners.weight[ c ] * bakerVisibility( bakerPoolProbe( corners, c ), n );
  return v;
}
`;

// The GLSL for adaptive volumes, to declare after BAKER_IRRADIANCE_GLSL: the level choice shared
// with the desktop decoders (shaders/baker_adaptive.glsl, fetched beside this module) and the
// WebGL reads above.
export async function adaptiveGlsl( url = new URL( '../shaders/baker_adaptive.glsl', import.meta.url ) ) {
	const response = await fetch( url );
	if ( ! response.ok ) throw new Error( `${ url }: ${ response.status } ${ response.statusText }` );
	return `${ await response.text() }\n${ BAKER_ADAPTIVE_WEBGL_GLSL }`;
}
