// The Bevy export read by an independent KTX2 parser (ktx-parse) and laid out as Bevy's shader
// reads it (irradiance_volume.wgsl): each texel must equal baker sample's irradiance at that
// probe for the face's normal, over π (Bevy multiplies by intensity and diffuse colour only),
// within RGB9E5's precision.
import fs from 'node:fs';
import path from 'node:path';
import { read } from 'ktx-parse';
import { bake, check, finish, freshDirectory, sample, sourceDir } from './support.mjs';

const VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 = 123;
const EXPONENT_FLAG = 0x20;
const scene = path.join( sourceDir, 'data/default_room/default_room.gltf' );
const dir = freshDirectory( 'bevy' );

// RGB9E5: three 9-bit mantissas without an implicit one, a shared 5-bit exponent of bias 15.
function decodeTexel( word ) {
	const exponent = word >>> 27;
	const step = Math.pow( 2, exponent - 15 - 9 );
	return { rgb: [ 0, 9, 18 ].map( ( shift ) => ( ( word >>> shift ) & 0x1ff ) * step ), step };
}

function checkHeader( ktx, resolution, name ) {
	const [ rx, ry, rz ] = resolution;
	check( ktx.vkFormat === VK_FORMAT_E5B9G9R9_UFLOAT_PACK32, `${ name }: vkFormat ${ ktx.vkFormat }` );
	check( ktx.typeSize === 4, `${ name }: typeSize ${ ktx.typeSize }` );
	check( ktx.pixelWidth === rx && ktx.pixelHeight === 2 * ry && ktx.pixelDepth === 3 * rz,
		`${ name }: ${ ktx.pixelWidth } × ${ ktx.pixelHeight } × ${ ktx.pixelDepth } for probes ${ resolution }` );
	check( ktx.layerCount === 0 && ktx.faceCount === 1 && ktx.levels.length === 1 && ktx.supercompressionScheme === 0,
		`${ name }: one level of one 3D texture, uncompressed` );
	const dfd = ktx.dataFormatDescriptor[ 0 ];
	check( dfd.colorModel === 1 && dfd.transferFunction === 1 && dfd.bytesPlane[ 0 ] === 4, `${ name }: RGBSDA, linear, 4 bytes` );
	const s = dfd.samples;
	check( s.length === 6, `${ name }: ${ s.length } DFD samples, expected 6` );
	for ( let c = 0; c < 3 && s.length === 6; ++ c ) {
		const mantissa = s[ 2 * c ], exponent = s[ 2 * c + 1 ];
		check( mantissa.bitOffset === 9 * c && mantissa.bitLength === 8 && mantissa.channelType === c && mantissa.sampleUpper === 8448,
			`${ name }: mantissa sample of channel ${ c }: ${ JSON.stringify( mantissa ) }` );
		check( exponent.bitOffset === 27 && exponent.bitLength === 4 && exponent.channelType === ( c | EXPONENT_FLAG ) &&
			exponent.sampleLower === 15 && exponent.sampleUpper === 31, `${ name }: exponent sample of channel ${ c }` );
	}
	check( String( ktx.keyValue.KTXwriter ).startsWith( 'baker ' ), `${ name }: KTXwriter ${ ktx.keyValue.KTXwriter }` );
}

// Every probe and face against baker sample of the same bake written as .vdb.
function checkTexels( exportDir, vdb, name ) {
	const sidecar = JSON.parse( fs.readFileSync( path.join( exportDir, 'irradiance_volume.json' ), 'utf8' ) );
	const bytes = fs.readFileSync( path.join( exportDir, sidecar.texture ) );
	const ktx = read( new Uint8Array( bytes ) );
	const [ rx, ry, rz ] = sidecar.resolution;
	checkHeader( ktx, sidecar.resolution, name );
	check( sidecar.intensity === 1, `${ name }: intensity ${ sidecar.intensity }` );
	const level = ktx.levels[ 0 ].levelData;
	const words = new DataView( level.buffer, level.byteOffset, level.byteLength );
	const { translation, scale } = sidecar.transform;
	let worst = 0, texels = 0;
	for ( let k = 0; k < rz; ++ k ) for ( let j = 0; j < ry; ++ j ) for ( let i = 0; i < rx; ++ i ) {
		// Bevy: probes at the cell centres of the unit cube the transform maps onto the volume.
		const unit = [ ( i + 0.5 ) / rx - 0.5, ( j + 0.5 ) / ry - 0.5, ( k + 0.5 ) / rz - 0.5 ];
		const at = unit.map( ( u, a ) => translation[ a ] + scale[ a ] * u );
		for ( let axis = 0; axis < 3; ++ axis ) for ( const negative of [ false, true ] ) {
			const normal = [ 0, 0, 0 ];
			normal[ axis ] = negative ? - 1 : 1;
			// The shader's layout: x = i; y = j, + Ry for a negative face; z = k + axis·Rz.
			const x = i, y = j + ( negative ? ry : 0 ), z = k + axis * rz;
			const texel = decodeTexel( words.getUint32( 4 * ( x + rx * ( y + 2 * ry * z ) ), true ) );
			const expected = sample( vdb, at, normal ).irradiance.map( ( e ) => Math.max( 0, e ) / Math.PI );
			for ( let c = 0; c < 3; ++ c ) {
				const error = Math.abs( texel.rgb[ c ] - expected[ c ] );
				const allowed = 0.5 * texel.step * ( 1 + 1e-6 ) + 1e-5 * expected[ c ];
				worst = Math.max( worst, error / allowed );
				check( error <= allowed, `${ name }: probe (${ i }, ${ j }, ${ k }) face ${ negative ? '-' : '+' }${ 'XYZ'[ axis ] } channel ${ c }: ` +
					`texel ${ texel.rgb[ c ] }, baker sample ${ expected[ c ] }` );
			}
			++ texels;
		}
	}
	console.log( `${ name }: ${ texels } texels of ${ rx } × ${ ry } × ${ rz } probes; largest error ${ worst.toFixed( 3 ) } of RGB9E5's half step` );
}

for ( const basis of [ 'ambient-cube', 'sh-l2' ] ) {
	// A bake for Bevy solves an ambient cube for coefficients ≥ 0; the .vdb is asked for the same.
	const fit = basis === 'ambient-cube' ? [ '--non-negative' ] : [];
	const common = [ scene, '--basis', basis, '--rays', '64', '--spacing', '1.5', '--seed', '5', ...fit ];
	const exported = bake( [ ...common, '--format', 'bevy', '--out', `${ basis }_bevy` ], dir );
	bake( [ ...common, '--out', `${ basis }.vdb` ], dir );
	check( exported.format === 'bevy' && exported.engine_export.engine === 'bevy', `${ basis }: summary names the format` );
	if ( basis === 'sh-l2' ) console.log( `sh-l2: ${ exported.engine_export.clamped_values } values clamped at 0` );
	else check( exported.engine_export.clamped_values === 0, `${ basis }: ${ exported.engine_export.clamped_values } values clamped` );
	checkTexels( path.join( dir, `${ basis }_bevy` ), path.join( dir, `${ basis }.vdb` ), basis );
}
finish( 'bevy KTX2' );
