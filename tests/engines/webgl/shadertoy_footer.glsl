
out vec4 shadertoy_out_color;
void main( void )
{
    shadertoy_out_color = vec4(1.0,1.0,1.0,1.0);
    vec4 color = vec4(1e20);
    mainImage( color, gl_FragCoord.xy );
    shadertoy_out_color = vec4(color.xyz,1.0);
}
