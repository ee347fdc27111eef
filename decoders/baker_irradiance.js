// baker_irradiance.js — the reference decoder of decoders/baker_irradiance.h, in JavaScript (an
// ES module, no dependencies): every basis, in double precision, with the same formulas and the
// same names. A volume stores, per probe, the coefficients of the irradiance
// E(n) = ∫ L(ω) max(0, n·ω) dω in one basis ("baker.basis"), channel after channel of the
// basis's colour space (RGB, or YCoCg for ad-ycocg). docs/DECODERS.md has the formulas.
//
//   import { BasisDecoder } from './baker_irradiance.js';
//   const decoder = new BasisDecoder( 'ad-ycocg' );    // sg-N: pass the "sharpness" of baker.reconstruction
//   const [ r, g, b ] = decoder.irradiance( probeCoefficients, [ 0, 1, 0 ] );
//
// A radiance volume ("signal": "radiance" in baker.reconstruction) holds L(ω) in the same
// functions: radiance(), irradianceFromRadiance() and specular() decode it, as in the header.

const PHI = 0.61803398874989484820; // (√5 − 1)/2
const MAX_SH_ORDER = 64;
const MAX_LOBES = 64;

function dot( a, b ) { return a[ 0 ] * b[ 0 ] + a[ 1 ] * b[ 1 ] + a[ 2 ] * b[ 2 ]; }
function cross( a, b ) { return [ a[ 1 ] * b[ 2 ] - a[ 2 ] * b[ 1 ], a[ 2 ] * b[ 0 ] - a[ 0 ] * b[ 2 ], a[ 0 ] * b[ 1 ] - a[ 1 ] * b[ 0 ] ]; }
function normalize( v ) { const s = 1 / Math.sqrt( dot( v, v ) ); return [ s * v[ 0 ], s * v[ 1 ], s * v[ 2 ] ]; }

// The icosahedron of Ambient Dice, in the order of the coefficients: vertices 0–3 are
// (±1, ±Φ, 0), 4–7 (0, ±1, ±Φ), 8–11 (±Φ, 0, ±1) before normalising; bit 0 of the index is the
// sign of the first non-zero coordinate, bit 1 that of the second (1: negative).
export function icosahedronVertex( i ) {
	const first = ( i & 1 ) ? - 1 : 1, second = ( i & 2 ) ? - 1 : 1;
	switch ( i >> 2 ) {
		case 0: return normalize( [ first, second * PHI, 0 ] );
		case 1: return normalize( [ 0, first, second * PHI ] );
		default: return normalize( [ first * PHI, 0, second ] );
	}
}

// The frame of the Bézier variants' derivative data: t is the axis in which the vertex has a
// zero coordinate, b = v̂ × t.
function icosahedronTangent( i ) {
	switch ( i >> 2 ) {
		case 0: return [ 0, 0, 1 ];
		case 1: return [ 1, 0, 0 ];
		default: return [ 0, 1, 0 ];
	}
}
function icosahedronBitangent( i ) { return cross( icosahedronVertex( i ), icosahedronTangent( i ) ); }

const VERTICES = Array.from( { length: 12 }, ( _, i ) => icosahedronVertex( i ) );
const TANGENTS = Array.from( { length: 12 }, ( _, i ) => icosahedronTangent( i ) );
const BITANGENTS = Array.from( { length: 12 }, ( _, i ) => icosahedronBitangent( i ) );

// The triangle that contains d, with d's spherical barycentrics ([v̂0 v̂1 v̂2]⁻¹ d) and flat ones
// (those divided by their sum): mirror d into the positive octant, whose triangle has one vertex
// of each group, and swap a vertex when d lies beyond the plane through the opposite edge.
export function locateOnIcosahedron( d ) {
	const sx = d[ 0 ] < 0 ? 1 : 0, sy = d[ 1 ] < 0 ? 1 : 0, sz = d[ 2 ] < 0 ? 1 : 0;
	const ax = Math.abs( d[ 0 ] ), ay = Math.abs( d[ 1 ] ), az = Math.abs( d[ 2 ] );
	const phi2 = 1 - PHI; // Φ² = 1 − Φ
	let a = sx + 2 * sy, b = 4 + sy + 2 * sz, c = 8 + sx + 2 * sz;
	if ( phi2 * ax - PHI * ay + az <= 0 ) c = b ^ 2;
	else if ( - PHI * ax + ay + phi2 * az <= 0 ) b = a ^ 2;
	else if ( ax + phi2 * ay - PHI * az <= 0 ) a = c ^ 1;
	const v0 = VERTICES[ a ], v1 = VERTICES[ b ], v2 = VERTICES[ c ];
	const r0 = cross( v1, v2 ), r1 = cross( v2, v0 ), r2 = cross( v0, v1 );
	const determinant = dot( v0, r0 );
	const spherical = [ dot( d, r0 ) / determinant, dot( d, r1 ) / determinant, dot( d, r2 ) / determinant ];
	const sum = spherical[ 0 ] + spherical[ 1 ] + spherical[ 2 ];
	return { vertex: [ a, b, c ], spherical, flat: spherical.map( ( s ) => s / sum ) };
}

// Lobe i of N spherical Gaussians sits on spherical Fibonacci point i of N.
export function sphericalFibonacciAxis( i, n ) {
	const z = 1 - ( 2 * i + 1 ) / n;
	const r = Math.sqrt( Math.max( 0, 1 - z * z ) );
	const phi = Math.PI * ( 3 - Math.sqrt( 5 ) ) * i;
	return [ r * Math.cos( phi ), r * Math.sin( phi ), z ];
}

// Real SH without the Condon–Shortley phase, polar axis z, through the recurrences of the
// normalised Legendre functions (they stay in range at any order); (x + iy)^m replaces angles.
// bandScale: null, or a factor per band l (the clamped cosine's, for irradiance from radiance).
function accumulateSphericalHarmonics( order, coefficients, offset, arrays, d, sums, bandScale = null ) {
	const count = ( order + 1 ) * ( order + 1 );
	let re = 1, im = 0, diagonal = Math.sqrt( 1 / ( 4 * Math.PI ) );
	for ( let m = 0; m <= order; ++ m ) {
		if ( m > 0 ) {
			const nextRe = re * d[ 0 ] - im * d[ 1 ];
			im = re * d[ 1 ] + im * d[ 0 ];
			re = nextRe;
			diagonal *= Math.sqrt( ( 2 * m + 1 ) / ( 2 * m ) );
		}
		let previous = 0, current = diagonal;
		for ( let l = m; l <= order; ++ l ) {
			if ( l > m ) {
				const a = Math.sqrt( ( 4 * l * l - 1 ) / ( l * l - m * m ) );
				const b = Math.sqrt( ( ( l - 1 ) * ( l - 1 ) - m * m ) / ( 4 * ( l - 1 ) * ( l - 1 ) - 1 ) );
				const next = a * ( d[ 2 ] * current - b * previous );
				previous = current;
				current = next;
			}
			const centre = l * l + l, scaled = bandScale ? bandScale[ l ] * current : current;
			for ( let k = 0; k < arrays; ++ k ) {
				const c = offset + k * count;
				if ( m === 0 ) sums[ k ] += scaled * coefficients[ c + centre ];
				else sums[ k ] += Math.SQRT2 * scaled * ( re * coefficients[ c + centre + m ] + im * coefficients[ c + centre - m ] );
			}
		}
	}
}

// ---- Relighting at run time (docs/RELIGHTING.md) ----
// A sky is 27 numbers: its radiance's real SH to band 2, L_lm = ∫ L(ω) Y_lm(ω) dω in world axes
// (index l² + l + m), R's nine, then G's, then B's. Its irradiance on an unoccluded surface of unit
// normal n: E(n) = Σ A_l L_lm Y_lm(n), A = π, 2π/3, π/4.
export function skyIrradiance( sky, n ) {
	const sums = [ 0, 0, 0 ];
	accumulateSphericalHarmonics( 2, sky, 0, 3, n, sums, [ Math.PI, 2 * Math.PI / 3, Math.PI / 4 ] );
	return sums;
}

// E(n) = E_rest(n) + V(n)·E_sky(n): the light that is not the sky's plus the new sky seen through
// the probe's cosine-weighted sky visibility.
function relit( rest, visibility, sky ) { return rest.map( ( e, c ) => e + visibility * sky[ c ] ); }

// A_l = 2π ∫₀¹ t P_l(t) dt: how the clamped cosine scales band l (π, 2π/3, π/4, 0, −π/24, …).
export function clampedCosineBand( l ) {
	if ( l === 0 ) return Math.PI;
	if ( l === 1 ) return 2 * Math.PI / 3;
	if ( l % 2 === 1 ) return 0;
	let ratio = 1; // l!/(2^l ((l/2)!)²), as a product that stays in range
	for ( let k = 1; k <= l / 2; ++ k ) ratio *= ( l / 2 + k ) / ( 4 * k );
	const sign = ( l / 2 - 1 ) % 2 === 0 ? 1 : - 1;
	return 2 * Math.PI * sign / ( ( l + 2 ) * ( l - 1 ) ) * ratio;
}

// Σ_l k[l] P_l(x) by the three-term recurrence.
function legendreSeries( k, x ) {
	if ( k.length === 0 ) return 0;
	let sum = k[ 0 ], previous = 1, current = x;
	for ( let l = 1; l < k.length; ++ l ) {
		if ( l > 1 ) {
			const next = ( ( 2 * l - 1 ) * x * current - ( l - 1 ) * previous ) / l;
			previous = current;
			current = next;
		}
		sum += k[ l ] * current;
	}
	return sum;
}

// The function sets whose functions are one profile of the cosine to their own axes.
const RADIAL = [ 'icosahedron-lobes', 'cube-lobes', 'spherical-gaussians', 'hemisphere-lobes' ];

// Responses of max(0, t)² and max(0, t)⁴: π(1 + x)²/8 and π(1/16 + x/6 + x²/8 − x⁴/48), as Legendre series.
function clampedLobeResponse( cos2, cos4 ) {
	const square = [ Math.PI / 6, Math.PI / 4, Math.PI / 12, 0, 0 ], fourth = [ Math.PI / 10, Math.PI / 6, Math.PI / 14, 0, - Math.PI / 210 ];
	return square.map( ( k, l ) => cos2 * k + cos4 * fourth[ l ] );
}

const CUBE_AXES = [ [ 1, 0, 0 ], [ - 1, 0, 0 ], [ 0, 1, 0 ], [ 0, - 1, 0 ], [ 0, 0, 1 ], [ 0, 0, - 1 ] ];

// The cubic Bézier patch of one triangle (Ambient Dice §2.3.1): corners are the vertex values,
// edge points add the stored gradient along the edge, and the centre blends three points, each
// of which makes the patch C1 across one edge.
function bezierPatch( t, spherical, data, offset ) {
	const root5 = Math.sqrt( 5 );
	const vertexFactor = spherical ? 1 / root5 : 1;
	const a0 = spherical ? ( root5 - 5 ) / 40 : - 0.25;
	const a1 = spherical ? ( 11 * root5 - 15 ) / 40 : 0.25;
	const a2 = spherical ? root5 / 10 : 0.5;
	const alpha = 0.5 * Math.sqrt( ( 5 + root5 ) / 2 );
	const b = spherical ? t.spherical : t.flat;
	const corner = [ 0, 0, 0 ], gradient = [ null, null, null ], edge = [ [ 0, 0, 0 ], [ 0, 0, 0 ], [ 0, 0, 0 ] ];
	for ( let k = 0; k < 3; ++ k ) {
		const v = t.vertex[ k ], at = offset + 3 * v;
		corner[ k ] = data[ at ];
		const tangent = TANGENTS[ v ], bitangent = BITANGENTS[ v ];
		gradient[ k ] = [ 0, 1, 2 ].map( ( a ) => data[ at + 1 ] * tangent[ a ] + data[ at + 2 ] * bitangent[ a ] );
	}
	for ( let k = 0; k < 3; ++ k ) for ( let m = 0; m < 3; ++ m ) {
		edge[ k ][ m ] = vertexFactor * corner[ k ] + ( root5 / 2 ) * dot( VERTICES[ t.vertex[ m ] ], gradient[ k ] ) / ( 3 * alpha );
	}
	let value = 0;
	for ( let k = 0; k < 3; ++ k ) {
		value += b[ k ] * b[ k ] * b[ k ] * corner[ k ];
		for ( let m = 0; m < 3; ++ m ) if ( m !== k ) value += 3 * b[ k ] * b[ k ] * b[ m ] * edge[ k ][ m ];
	}
	const p = b.map( ( x ) => Math.max( 0, x ) );
	const weightSum = p[ 1 ] * p[ 2 ] + p[ 0 ] * p[ 2 ] + p[ 0 ] * p[ 1 ];
	if ( weightSum <= 0 ) return value;
	let centre = 0;
	for ( let j = 0; j < 3; ++ j ) {
		const k = ( j + 1 ) % 3, m = ( j + 2 ) % 3;
		const w = p[ k ] * p[ m ] / weightSum;
		centre += w * ( a0 * ( corner[ k ] + corner[ m ] ) + a1 * ( edge[ k ][ m ] + edge[ m ][ k ] ) + a2 * ( edge[ k ][ j ] + edge[ m ][ j ] ) );
	}
	return value + 6 * b[ 0 ] * b[ 1 ] * b[ 2 ] * centre;
}

// A function set: what one colour channel's coefficients are coefficients of.
export class FunctionSet {
	constructor( kind, options = {} ) {
		this.kind = kind; // 'sh', 'icosahedron-linear', 'icosahedron-lobes', 'icosahedron-bezier', 'cube-lobes', 'spherical-gaussians', 'hemisphere-lobes'
		this.shOrder = options.shOrder ?? 0;
		this.spherical = options.spherical ?? true; // barycentrics of the linear and Bézier sets
		this.cos2 = options.cos2 ?? 0;
		this.cos4 = options.cos4 ?? 0;
		this.sharpness = options.sharpness ?? 0;
		this.axes = options.axes ?? [];
		// Radiance: the radial lobes' diffuse response Σ_l response[l] P_l(axis·n); empty when unknown.
		this.response = options.response ?? [];
	}

	get count() {
		switch ( this.kind ) {
			case 'sh': return ( this.shOrder + 1 ) * ( this.shOrder + 1 );
			case 'icosahedron-linear': case 'icosahedron-lobes': return 12;
			case 'icosahedron-bezier': return 36;
			case 'cube-lobes': return 6;
			default: return this.axes.length;
		}
	}

	// Σ_i coefficients[offset + k·count + i]·f_i(d) for k < arrays.
	expand( coefficients, offset, arrays, d ) {
		const count = this.count, sums = new Array( arrays ).fill( 0 );
		switch ( this.kind ) {
			case 'sh':
				accumulateSphericalHarmonics( this.shOrder, coefficients, offset, arrays, d, sums );
				break;
			case 'icosahedron-linear': {
				const t = locateOnIcosahedron( d ), b = this.spherical ? t.spherical : t.flat;
				for ( let k = 0; k < arrays; ++ k ) for ( let c = 0; c < 3; ++ c ) sums[ k ] += b[ c ] * coefficients[ offset + k * count + t.vertex[ c ] ];
				break;
			}
			case 'icosahedron-lobes':
				for ( let i = 0; i < 12; ++ i ) {
					const c = dot( VERTICES[ i ], d );
					if ( c <= 0 ) continue;
					const lobe = c * c * ( this.cos2 + this.cos4 * c * c );
					for ( let k = 0; k < arrays; ++ k ) sums[ k ] += lobe * coefficients[ offset + k * count + i ];
				}
				break;
			case 'icosahedron-bezier': {
				const t = locateOnIcosahedron( d );
				for ( let k = 0; k < arrays; ++ k ) sums[ k ] = bezierPatch( t, this.spherical, coefficients, offset + k * count );
				break;
			}
			case 'hemisphere-lobes':
				for ( let i = 0; i < this.axes.length; ++ i ) {
					const c = dot( this.axes[ i ], d );
					if ( c <= 0 ) continue;
					const lobe = c * c * ( this.cos2 + this.cos4 * c * c );
					for ( let k = 0; k < arrays; ++ k ) sums[ k ] += lobe * coefficients[ offset + k * count + i ];
				}
				break;
			case 'cube-lobes':
				for ( let a = 0; a < 3; ++ a ) {
					const lobe = 2 * a + ( d[ a ] < 0 ? 1 : 0 );
					for ( let k = 0; k < arrays; ++ k ) sums[ k ] += d[ a ] * d[ a ] * coefficients[ offset + k * count + lobe ];
				}
				break;
			default:
				for ( let i = 0; i < this.axes.length; ++ i ) {
					const lobe = Math.exp( this.sharpness * ( dot( this.axes[ i ], d ) - 1 ) );
					for ( let k = 0; k < arrays; ++ k ) sums[ k ] += lobe * coefficients[ offset + k * count + i ];
				}
		}
		return sums;
	}

	// Σ_i coefficients[offset + k·count + i]·K_i(n), K_i(n) = ∫ f_i(ω) max(0, n·ω) dω; null when
	// the set's response is not known here (the piecewise Ambient Dice sets, sg-N without its series).
	expandIrradianceFromRadiance( coefficients, offset, arrays, n ) {
		const count = this.count, sums = new Array( arrays ).fill( 0 );
		if ( this.kind === 'sh' ) {
			const bands = Array.from( { length: this.shOrder + 1 }, ( _, l ) => clampedCosineBand( l ) );
			accumulateSphericalHarmonics( this.shOrder, coefficients, offset, arrays, n, sums, bands );
			return sums;
		}
		if ( ! RADIAL.includes( this.kind ) || this.response.length === 0 ) return null;
		const axes = this.kind === 'icosahedron-lobes' ? VERTICES : this.kind === 'cube-lobes' ? CUBE_AXES : this.axes;
		for ( let i = 0; i < count; ++ i ) {
			const response = legendreSeries( this.response, dot( axes[ i ], n ) );
			for ( let k = 0; k < arrays; ++ k ) sums[ k ] += response * coefficients[ offset + k * count + i ];
		}
		return sums;
	}
}

// Glossy specular: "baker.specular"'s diffuse_weight or albedo ([roughness node j][n·v node k],
// nodes j/15 and k/15), bilinear with both arguments clamped to [0, 1].
export function specularTableLookup( table, roughness, cosView ) {
	const last = table.length - 1;
	const x = Math.min( Math.max( roughness, 0 ), 1 ) * last, y = Math.min( Math.max( cosView, 0 ), 1 ) * last;
	const j = Math.min( Math.floor( x ), last - 1 ), k = Math.min( Math.floor( y ), last - 1 ), fx = x - j, fy = y - k;
	return ( 1 - fx ) * ( ( 1 - fy ) * table[ j ][ k ] + fy * table[ j ][ k + 1 ] ) + fx * ( ( 1 - fy ) * table[ j + 1 ][ k ] + fy * table[ j + 1 ][ k + 1 ] );
}

// n·v clamped to [1e-4, 1] in the plane of n and v (a view at or below the surface is taken just
// above it), and the mirror direction 2(n·v)n − v of that view.
export function specularView( n, v ) {
	const nv = dot( n, v );
	let along = [ v[ 0 ] - nv * n[ 0 ], v[ 1 ] - nv * n[ 1 ], v[ 2 ] - nv * n[ 2 ] ];
	if ( Math.sqrt( dot( along, along ) ) < 1e-12 ) {
		// v along n: any tangent (this one is Eigen's unitOrthogonal, as the library's).
		const tiny = 1e-12 * Math.abs( n[ 2 ] );
		along = Math.abs( n[ 0 ] ) > tiny || Math.abs( n[ 1 ] ) > tiny ? [ - n[ 1 ], n[ 0 ], 0 ] : [ 0, - n[ 2 ], n[ 1 ] ];
	}
	const t = normalize( along ), cosView = Math.min( Math.max( nv, 1e-4 ), 1 ), sinView = Math.sqrt( 1 - cosView * cosView );
	const reflection = [ 0, 1, 2 ].map( ( a ) => 2 * cosView * n[ a ] - ( cosView * n[ a ] + sinView * t[ a ] ) );
	return { cosView, reflection };
}

function numberAfter( name, prefix, low, high ) {
	if ( ! name.startsWith( prefix ) ) return - 1;
	const digits = name.slice( prefix.length );
	if ( ! /^(0|[1-9][0-9]?)$/.test( digits ) ) return - 1;
	const value = Number( digits );
	return value >= low && value <= high ? value : - 1;
}

// A basis by its name in "baker.basis". valid is false for an unknown name, or sg-N without λ.
export class BasisDecoder {
	constructor( basisName, sgSharpness = 0 ) {
		this.ycocg = false;
		this.primary = null; // every channel's functions, or Y's for YCoCg
		this.chroma = null; // Co's and Cg's for YCoCg
		this.valid = this.#parse( basisName, sgSharpness );
	}

	functions( channel ) { return this.ycocg && channel > 0 ? this.chroma : this.primary; }
	coefficientCount( channel ) { return this.functions( channel ).count; }
	coefficientOffset( channel ) {
		let offset = 0;
		for ( let c = 0; c < channel; ++ c ) offset += this.coefficientCount( c );
		return offset;
	}
	get coefficientsPerProbe() { return this.coefficientOffset( 3 ); }

	// Lobe axes as listed in "baker.reconstruction" ([x, y, z] per lobe) for sg-N and ad-hemi9, in
	// place of the built-in ones (ad-hemi9's are about +Y: a volume baked about another axis needs these).
	setLobeAxes( axes ) { this.primary.axes = axes.map( ( a ) => [ a[ 0 ], a[ 1 ], a[ 2 ] ] ); }

	// RGB irradiance at unit normal n from one probe's coefficients, starting at `offset`.
	irradiance( coefficients, n, offset = 0 ) {
		if ( ! this.ycocg ) return this.primary.expand( coefficients, offset, 3, n );
		const [ y ] = this.primary.expand( coefficients, offset, 1, n );
		const [ co, cg ] = this.chroma.expand( coefficients, offset + this.primary.count, 2, n );
		return [ y + co - cg, y + cg, y - co - cg ];
	}

	// Sky visibility (1/π)∫V max(0, n·ω) dω from one probe's visibility values (channel 0's functions).
	visibility( coefficients, n, offset = 0 ) { return this.primary.expand( coefficients, offset, 1, n )[ 0 ]; }

	// Irradiance under a sky an engine swaps at run time: `rest` holds one probe's coefficients
	// less its sky_direct grids' (the light that is not the sky's: interpolate it like
	// coefficients), `visibility` its visibility values, `sky` the new sky (skyIrradiance).
	relitIrradiance( rest, visibility, n, sky, restOffset = 0, visibilityOffset = 0 ) {
		return relit( this.irradiance( rest, n, restOffset ), this.visibility( visibility, n, visibilityOffset ), skyIrradiance( sky, n ) );
	}

	// ---- Radiance volumes ("signal": "radiance") ----

	// The lobes' response series: "diffuse_response"."coefficients" of the function set in
	// "baker.reconstruction". sg-N needs it; ad-cos2, ad-srbf and ambient-cube have it built in.
	// False for the other bases.
	setDiffuseResponse( legendre ) {
		if ( this.ycocg || ! RADIAL.includes( this.primary.kind ) || legendre.length < 1 ) return false;
		this.primary.response = Array.from( legendre );
		return true;
	}

	// SH and the radial lobes (sg-N after setDiffuseResponse); not the piecewise Ambient Dice variants.
	get decodesRadiance() {
		return ! this.ycocg && ( this.primary.kind === 'sh' || this.primary.response.length > 0 );
	}

	// RGB radiance L(d) arriving from unit direction d.
	radiance( coefficients, d, offset = 0 ) { return this.irradiance( coefficients, d, offset ); }

	// RGB irradiance E(n) = ∫ L(ω) max(0, n·ω) dω; null unless decodesRadiance.
	irradianceFromRadiance( coefficients, n, offset = 0 ) {
		return this.ycocg ? null : this.primary.expandIrradianceFromRadiance( coefficients, offset, 3, n );
	}

	// Sky visibility (1/π)∫V(ω) max(0, n·ω) dω from the stored V(ω); null unless decodesRadiance.
	visibilityFromRadiance( coefficients, n, offset = 0 ) {
		const sums = this.ycocg ? null : this.primary.expandIrradianceFromRadiance( coefficients, offset, 1, n );
		return sums && sums[ 0 ] / Math.PI;
	}

	// relitIrradiance for a radiance volume's coefficients; null unless decodesRadiance.
	relitIrradianceFromRadiance( rest, visibility, n, sky, restOffset = 0, visibilityOffset = 0 ) {
		const e = this.irradianceFromRadiance( rest, n, restOffset );
		return e && relit( e, this.visibilityFromRadiance( visibility, n, visibilityOffset ), skyIrradiance( sky, n ) );
	}

	// GGX (F0 = 1, α = roughness²) mean radiance S = (1 − w)·L(r) + w·E(n)/π at unit normal n and
	// unit view v (towards the viewer); table is "baker.specular" ({ diffuse_weight, albedo }).
	// { value: [r, g, b], albedo, diffuseWeight }; null unless decodesRadiance.
	specular( coefficients, n, v, roughness, table, offset = 0 ) {
		const e = this.irradianceFromRadiance( coefficients, n, offset );
		if ( ! e ) return null;
		const view = specularView( n, v );
		const w = specularTableLookup( table.diffuse_weight, roughness, view.cosView );
		const mirror = this.radiance( coefficients, view.reflection, offset );
		return { value: mirror.map( ( l, c ) => ( 1 - w ) * l + w * e[ c ] / Math.PI ), albedo: specularTableLookup( table.albedo, roughness, view.cosView ), diffuseWeight: w };
	}

	#parse( name, sgSharpness ) {
		const shOrder = numberAfter( name, 'sh-l', 0, MAX_SH_ORDER );
		const lobes = numberAfter( name, 'sg-', 1, MAX_LOBES );
		if ( shOrder >= 0 ) {
			this.primary = new FunctionSet( 'sh', { shOrder } );
		} else if ( lobes >= 1 ) {
			if ( ! ( sgSharpness > 0 ) ) return false;
			const axes = Array.from( { length: lobes }, ( _, i ) => sphericalFibonacciAxis( i, lobes ) );
			this.primary = new FunctionSet( 'spherical-gaussians', { sharpness: sgSharpness, axes } );
		} else if ( name === 'ad-linear' ) {
			this.primary = new FunctionSet( 'icosahedron-linear', { spherical: false } );
		} else if ( name === 'ad-cos2' || name === 'ad-srbf' ) {
			// ad-srbf is the paper's 0.7·c² + 0.3·c⁴; both normalised so that the 12 lobes sum to
			// 1, from Σ max(0, v̂·n)² = 2 and Σ max(0, v̂·n)⁴ = 6/5 over the vertices.
			const paper = name === 'ad-srbf', w2 = paper ? 0.7 : 1, w4 = paper ? 0.3 : 0;
			const scale = 1 / ( 2 * w2 + 1.2 * w4 ), cos2 = scale * w2, cos4 = scale * w4;
			this.primary = new FunctionSet( 'icosahedron-lobes', { cos2, cos4, response: clampedLobeResponse( cos2, cos4 ) } );
		} else if ( name === 'ad-hemi9' ) {
			// ad-srbf's lobe on the icosahedron turned so that the face centre (1, 1, 1)/√3 points
			// along +Y (about (−1, 0, 1)/√2 through arccos(1/√3)), keeping the 9 vertices with y > −1/2.
			const c = 1 / Math.sqrt( 3 ), s = Math.sqrt( 2 / 3 ), k = [ - Math.SQRT1_2, 0, Math.SQRT1_2 ];
			const axes = VERTICES.map( ( v ) => {
				const kv = cross( k, v ), kd = dot( k, v );
				return [ 0, 1, 2 ].map( ( a ) => c * v[ a ] + s * kv[ a ] + ( 1 - c ) * kd * k[ a ] );
			} ).filter( ( a ) => a[ 1 ] > - 0.5 );
			const cos2 = 0.7 / 1.76, cos4 = 0.3 / 1.76;
			this.primary = new FunctionSet( 'hemisphere-lobes', { cos2, cos4, axes, response: clampedLobeResponse( cos2, cos4 ) } );
		} else if ( name === 'ad-rgb' || name === 'ad-rgb-flat' ) {
			this.primary = new FunctionSet( 'icosahedron-bezier', { spherical: name === 'ad-rgb' } );
		} else if ( name === 'ad-ycocg' ) {
			this.ycocg = true;
			this.primary = new FunctionSet( 'icosahedron-bezier', { spherical: true } );
			this.chroma = new FunctionSet( 'icosahedron-linear', { spherical: true } );
		} else if ( name === 'ambient-cube' ) {
			this.primary = new FunctionSet( 'cube-lobes', { response: [ Math.PI / 6, Math.PI / 4, Math.PI / 12 ] } ); // π(1 + x)²/8
		} else {
			return false;
		}
		return true;
	}
}

// The eight probes around `position` and their weights (corner c: +1 along x if c & 1, y if
// c & 2, z if c & 4); outside the grid the nearest probes on its boundary, like clamp-to-edge.
// Probe (i, j, k) sits at origin + spacing·(i, j, k) and is number i + nx·(j + ny·k).
export function probeNeighbourhood( position, origin, spacing, dims ) {
	const low = [ 0, 0, 0 ], high = [ 0, 0, 0 ], fraction = [ 0, 0, 0 ];
	for ( let a = 0; a < 3; ++ a ) {
		const g = Math.min( Math.max( ( position[ a ] - origin[ a ] ) / spacing, 0 ), dims[ a ] - 1 );
		low[ a ] = Math.floor( g );
		if ( low[ a ] > dims[ a ] - 2 ) low[ a ] = dims[ a ] > 1 ? dims[ a ] - 2 : 0;
		high[ a ] = dims[ a ] > 1 ? low[ a ] + 1 : 0;
		fraction[ a ] = g - low[ a ];
	}
	const probe = [], weight = [];
	for ( let c = 0; c < 8; ++ c ) {
		const i = ( c & 1 ) ? high[ 0 ] : low[ 0 ], j = ( c & 2 ) ? high[ 1 ] : low[ 1 ], k = ( c & 4 ) ? high[ 2 ] : low[ 2 ];
		probe.push( i + dims[ 0 ] * ( j + dims[ 1 ] * k ) );
		weight.push( ( ( c & 1 ) ? fraction[ 0 ] : 1 - fraction[ 0 ] ) * ( ( c & 2 ) ? fraction[ 1 ] : 1 - fraction[ 1 ] ) *
			( ( c & 4 ) ? fraction[ 2 ] : 1 - fraction[ 2 ] ) );
	}
	return { probe, weight };
}

// One interpolated probe: Σ_c weight[c]·values[probe[c]·count + i] for i < count.
export function blendProbes( values, neighbourhood, count ) {
	const out = new Float64Array( count );
	for ( let c = 0; c < 8; ++ c ) {
		const w = neighbourhood.weight[ c ], base = neighbourhood.probe[ c ] * count;
		if ( w === 0 ) continue;
		for ( let i = 0; i < count; ++ i ) out[ i ] += w * values[ base + i ];
	}
	return out;
}

// Leak-aware weights (docs/LEAKS.md): a volume with "baker.distance_map" holds per probe an N × N
// octahedral map of the mean and mean squared distance to the first surface, in units of the
// map's cap (value 2t and 2t + 1 of texel t = i + N·j). Multiply each corner's trilinear weight
// by leakWeight() and divide by the sum of the products.

// Octahedral coordinates in [0, 1]² of unit d, +Y up (the file's "encoding").
export function octahedralEncode( d ) {
	const l1 = Math.abs( d[ 0 ] ) + Math.abs( d[ 1 ] ) + Math.abs( d[ 2 ] );
	let px = d[ 0 ] / l1, pz = d[ 2 ] / l1;
	if ( d[ 1 ] < 0 ) [ px, pz ] = [ ( 1 - Math.abs( pz ) ) * ( px < 0 ? - 1 : 1 ), ( 1 - Math.abs( px ) ) * ( pz < 0 ? - 1 : 1 ) ];
	return [ 0.5 * ( px + 1 ), 0.5 * ( pz + 1 ) ];
}

// The weight in (0, 1] of the probe baked at `probe` (grid position plus its probe_offset) with
// distance moments `moments` (2·size² values from `offset`), for a shading point on a surface of
// unit `normal`; map is { size, cap } of "baker.distance_map". 1 where its map reads open towards
// the point, else the back-face weight times Chebyshev's bound.
export function leakWeight( map, moments, probe, point, normal, spacing, offset = 0 ) {
	const fromProbe = [ 0, 1, 2 ].map( ( a ) => point[ a ] + 0.25 * spacing * normal[ a ] - probe[ a ] );
	const r = Math.sqrt( dot( fromProbe, fromProbe ) );
	if ( ! ( r > 0 ) || ! Number.isFinite( r ) ) return 1;
	const direction = fromProbe.map( ( x ) => x / r );
	const uv = octahedralEncode( direction ), n = map.size, low = [ 0, 0 ], f = [ 0, 0 ];
	for ( let a = 0; a < 2; ++ a ) {
		const x = uv[ a ] * n - 0.5;
		low[ a ] = Math.min( Math.max( Math.floor( x ), 0 ), n - 2 );
		f[ a ] = Math.min( Math.max( x - low[ a ], 0 ), 1 );
	}
	let mean = 0, meanSquare = 0, open = true;
	for ( let corner = 0; corner < 4; ++ corner ) {
		const di = corner & 1, dj = corner >> 1;
		const w = ( di ? f[ 0 ] : 1 - f[ 0 ] ) * ( dj ? f[ 1 ] : 1 - f[ 1 ] );
		const t = offset + 2 * ( low[ 0 ] + di + n * ( low[ 1 ] + dj ) );
		mean += w * moments[ t ];
		meanSquare += w * moments[ t + 1 ];
		if ( w > 0 && moments[ t ] < 1 ) open = false;
	}
	if ( open ) return 1;
	mean *= map.cap;
	meanSquare *= map.cap * map.cap;
	const facing = 0.5 * ( 1 - dot( direction, normal ) );
	let weight = ( facing * facing + 0.2 ) / 1.2;
	if ( r > mean ) {
		const variance = Math.abs( meanSquare - mean * mean ), beyond = r - mean;
		const chebyshev = variance / ( variance + beyond * beyond );
		weight *= chebyshev * chebyshev * chebyshev;
	}
	// The paper's floor and crush threshold, divided by 1.2 with its back-face weight.
	const floor = 1e-6 / 1.2, crush = 0.2 / 1.2;
	if ( ! ( weight >= floor ) ) weight = floor;
	if ( weight < crush ) weight *= weight * weight / ( crush * crush );
	return weight;
}

// Adaptive volumes (docs/ADAPTIVE.md): levels, coarsest first, each { origin, spacing, dims,
// subBricksHeld } where subBricksHeld[bx + Bx·(by + By·bz)] (B = ⌈dims / 8⌉) holds the sub-bricks of 4³
// the level holds of brick (bx, by, bz) of 8³ probes, bit s = sx + 2·sy + 4·sz for the probes with
// (i / 4) % 2 = sx and so on (0xFF the whole brick, 0 none), or is null when it holds every probe. The header's
// finestLevelNeighbourhood: the finest level whose probes of non-zero weight around `position` are
// all held; when none is (deep inside closed geometry), level 0 with its held probes' weights
// renormalised, or all zero when it holds none. Returns { level, probe, weight }.
function levelHoldsProbe( level, probe ) {
	if ( level.bricksHeld !== undefined ) throw new Error( 'bricksHeld (non-zero per held brick, format 4) is now subBricksHeld: a mask of sub-bricks per brick (format 5)' );
	if ( ! level.subBricksHeld ) return true;
	const [ nx, ny ] = level.dims;
	const i = probe % nx, j = Math.floor( probe / nx ) % ny, k = Math.floor( probe / ( nx * ny ) );
	const bx = Math.ceil( nx / 8 ), by = Math.ceil( ny / 8 );
	const subBrick = Math.floor( i / 4 ) % 2 + 2 * ( Math.floor( j / 4 ) % 2 ) + 4 * ( Math.floor( k / 4 ) % 2 );
	return ( ( level.subBricksHeld[ Math.floor( i / 8 ) + bx * ( Math.floor( j / 8 ) + by * Math.floor( k / 8 ) ) ] >> subBrick ) & 1 ) !== 0;
}

export function finestLevelNeighbourhood( position, levels ) {
	for ( let l = levels.length - 1; l > 0; -- l ) {
		const n = probeNeighbourhood( position, levels[ l ].origin, levels[ l ].spacing, levels[ l ].dims );
		if ( n.probe.every( ( p, c ) => n.weight[ c ] === 0 || levelHoldsProbe( levels[ l ], p ) ) ) return { level: l, ...n };
	}
	const n = probeNeighbourhood( position, levels[ 0 ].origin, levels[ 0 ].spacing, levels[ 0 ].dims );
	n.probe.forEach( ( p, c ) => { if ( ! levelHoldsProbe( levels[ 0 ], p ) ) n.weight[ c ] = 0; } );
	const total = n.weight.reduce( ( a, w ) => a + w, 0 );
	if ( total > 0 && total !== 1 ) n.weight = n.weight.map( ( w ) => w / total );
	return { level: 0, ...n };
}
