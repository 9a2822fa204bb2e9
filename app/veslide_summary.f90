!> The run summary the programs print after a single case (veslide, veslide-batch): read from
!> the case's results list, so that every number printed is the number written. The MPI program
!> (mpi/app) compiles this same file (mpi/app/veslide_summary.f90 links here).
module veslide_summary
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_version, only: version_string
    use veslide_case_data, only: case_t, case_spec_t
    use veslide_validity, only: surface_band
    use veslide_warning, only: warning_t, warning_line
    use veslide_quantities, only: results_t
    use veslide_device, only: device_info_t, device_info
    implicit none
    private
    public :: header_lines, summary_lines, summary_width, write_warnings

    !> The length of a line of the run summary: two texts of the input (up to 1023 characters
    !> each, the input's and the output's paths) and the words around them, never cut
    integer, parameter :: summary_width = 2200

contains

    !> Print `warnings` on `unit` (stderr), one line each, as "veslide: WHERE: warning [code]:
    !> text"; those about the input (source 'input') only with `with_input` (they are printed
    !> once, when the input is read). The programs print every warning, --quiet or not.
    subroutine write_warnings(unit, warnings, where, with_input)
        integer, intent(in) :: unit
        type(warning_t), intent(in) :: warnings(:)
        character(len=*), intent(in) :: where
        logical, intent(in) :: with_input
        integer :: k
        do k = 1, size(warnings)
            if (with_input .or. warnings(k)%source /= 'input') write (unit, '(a)') warning_line(warnings(k), where)
        end do
        flush (unit)
    end subroutine write_warnings

    !> The header of a run, printed before it starts: the program, the input and the output, and
    !> what is solved
    function header_lines(spec, output) result(lines)
        type(case_spec_t), intent(in) :: spec
        character(len=*), intent(in) :: output      !! the result file
        character(len=summary_width), allocatable :: lines(:)
        character(len=summary_width) :: b
        allocate (lines(0))
        b = "veslide "//version_string()//": "//spec%input_path//" -> "//output
        lines = [lines, b]
        write (b, '(a,i0,a,i0,a,a,a,a,a,a)') "  grid ", spec%nx, " x ", spec%ny, &
            ", surface ", spec%surface%kind, ", material ", spec%material%model, ", kernel ", spec%kernel_name()
        lines = [lines, b]
    end function header_lines

    !> The run summary a program prints after the solve, from the case's results `r` (one line per
    !> entry; the header, `header_lines`, is printed before the solve)
    function summary_lines(c, r) result(lines)
        type(case_t), intent(in) :: c
        type(results_t), intent(in) :: r
        character(len=summary_width), allocatable :: lines(:)
        character(len=summary_width) :: b
        real(dp) :: hrms
        hrms = r%get('rms_height_m')
        allocate (lines(0))
        if (c%grid%is_distributed()) then
            write (b, '(a,i0,a)') "  distributed over ", c%grid%ranks, " processes (rows of the grid)"
            lines = [lines, b]
        end if
        write (b, '(a,es12.5,a)') "  rms height            ", hrms, " m"; lines = [lines, b]
        write (b, '(a,es12.5,a)') "  nominal pressure      ", r%get('mean_pressure_pa'), " Pa"; lines = [lines, b]
        write (b, '(a,f12.8)') "  contact area fraction ", r%get('contact_area_fraction'); lines = [lines, b]
        write (b, '(a,es12.5,a,f9.5,a)') "  mean separation       ", r%get('mean_separation_m'), " m (", &
            r%get('mean_separation_m')/max(hrms, tiny(1.0_dp)), " h_rms)"
        lines = [lines, b]
        write (b, '(a,es12.5,a)') "  max pressure          ", r%get('max_pressure_pa'), " Pa"; lines = [lines, b]
        if (c%spec%law%adhesive()) then
            write (b, '(a,es12.5,a,f10.6,a)') "  adhesive pressure     ", r%get('adhesive_pressure_pa'), &
                " Pa, under tension ", r%get('adhesive_area_fraction'), " of the area"
            lines = [lines, b]
            call edge_line('trailing')
            call edge_line('leading')
        end if
        if (.not. c%kernel%symmetric .or. c%spec%shear_coefficient > 0.0_dp) then
            write (b, '(a,es12.5)') "  friction coefficient  ", r%get('friction_coefficient'); lines = [lines, b]
            if (c%spec%shear_coefficient > 0.0_dp) then
                write (b, '(a,es12.5,a,es12.5,a)') "    of which hysteresis ", r%get('friction_hysteresis'), &
                    ", interfacial ", r%get('friction_interfacial'), " (&interface shear_coefficient)"
                lines = [lines, b]
            end if
            write (b, '(a,es12.5)') "  lateral force ratio   ", r%get('lateral_force_ratio'); lines = [lines, b]
        end if
        if (.not. c%spec%material%solid%is_elastic()) then
            block
                real(dp) :: omega, td, qlo, qhi
                call c%spec%material%solid%loss_peak(omega, td)
                call surface_band(c%spec, c%grid, qlo, qhi)
                write (b, '(a,f6.3,a,es10.3,a)') "  loss peak             tan(delta) = ", td, " at ", omega, " rad/s"
                lines = [lines, b]
                write (b, '(a,es9.3,a,es9.3,a,es9.3,a)') "    met by the surface's q for speeds ", omega/qhi, " to ", &
                    omega/qlo, " m/s (this run ", norm2(c%spec%velocity()), ")"
                lines = [lines, b]
            end block
        end if
        write (b, '(a,a,a,i0,a,i0,a,es9.2,a,l1)') "  solver ", c%state%method, ": ", c%state%iterations, &
            " iterations, ", c%state%operator_applications, " FFT pairs, residual ", c%state%residual, &
            ", converged ", c%state%converged
        lines = [lines, b]
        if (c%state%device == 'gpu') then
            block
                type(device_info_t) :: info
                type(error_t), allocatable :: none
                call device_info(info, none)
                if (.not. allocated(none)) then
                    write (b, '(a,f0.3,a)') "  solved on the GPU "//info%name//" (set-up and transfers ", &
                        c%state%transfer_seconds, " s)"
                    lines = [lines, b]
                end if
            end block
        end if
        if (allocated(c%warnings)) then
            if (size(c%warnings) == 0) then
                b = "  validity              no warnings (what is checked: docs/validity.md)"
            else
                write (b, '(a,i0,a)') "  validity              ", size(c%warnings), " warning(s), on stderr and in /warnings: "// &
                    codes()
            end if
            lines = [lines, b]
        end if
        write (b, '(a,f8.3,a,f8.3,a,f8.3,a)') "  time: surface ", r%get('surface_seconds'), " s, kernel ", &
            r%get('kernel_seconds'), " s, solve ", r%get('solve_seconds'), " s"
        lines = [lines, b]
    contains
        !> The codes of the case's warnings, each once
        function codes() result(t)
            character(len=:), allocatable :: t
            integer :: k, j
            logical :: seen
            t = ''
            do k = 1, size(c%warnings)
                seen = .false.
                do j = 1, k - 1
                    if (c%warnings(j)%code == c%warnings(k)%code) seen = .true.
                end do
                if (seen) cycle
                if (len(t) > 0) t = t//", "
                t = t//c%warnings(k)%code
            end do
        end function codes

        !> The line of the contact's `side` edges ('trailing' or 'leading'): their mean G, or why none
        subroutine edge_line(side)
            character(len=*), intent(in) :: side
            character(len=24) :: label
            label = "  "//side//" edge"
            if (r%get(side//'_edges') > 0.0_dp) then
                write (b, '(a,a,es12.5,a,f9.5,a,i0,a)') label, "G = ", r%get(side//'_edge_energy_j_m2'), " J/m^2 (", &
                    r%get(side//'_edge_energy_j_m2')/r%get('adhesion_energy_j_m2'), " w), ", &
                    nint(r%get(side//'_edges')), " edge(s)"
            else
                b = label//"not measured (a line contact's crack-like edges only: docs/adhesion.md)"
            end if
            lines = [lines, b]
        end subroutine edge_line
    end function summary_lines

end module veslide_summary
