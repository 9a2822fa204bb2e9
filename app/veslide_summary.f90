!> The run summary the programs print after a single case (veslide, veslide-batch): read from
!> the case's results list, so that every number printed is the number written. The MPI program
!> (mpi/app) compiles this same file (mpi/app/veslide_summary.f90 links here).
module veslide_summary
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_version, only: version_string
    use veslide_case_data, only: case_t
    use veslide_quantities, only: results_t
    use veslide_device, only: device_info_t, device_info
    implicit none
    private
    public :: summary_lines, summary_width

    !> The length of a line of the run summary: two texts of the input (up to 1023 characters
    !> each, the input's and the output's paths) and the words around them, never cut
    integer, parameter :: summary_width = 2200

contains

    !> The run summary a program prints, from the case's results `r` (one line per entry)
    function summary_lines(c, r, output) result(lines)
        type(case_t), intent(in) :: c
        type(results_t), intent(in) :: r
        character(len=*), intent(in) :: output      !! the result file
        character(len=summary_width), allocatable :: lines(:)
        character(len=summary_width) :: b
        real(dp) :: hrms
        hrms = r%get('rms_height_m')
        allocate (lines(0))
        lines = [lines, b_("veslide "//version_string()//": "//c%spec%input_path//" -> "//output)]
        write (b, '(a,i0,a,i0,a,a,a,a,a,a)') "  grid ", c%grid%nx, " x ", c%grid%ny, &
            ", surface ", c%spec%surface%kind, ", material ", c%spec%material%model, ", kernel ", c%spec%kernel_name()
        lines = [lines, b]
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
        if (.not. c%kernel%symmetric) then
            write (b, '(a,es12.5)') "  friction coefficient  ", r%get('friction_coefficient'); lines = [lines, b]
            write (b, '(a,es12.5)') "  lateral force ratio   ", r%get('lateral_force_ratio'); lines = [lines, b]
        end if
        if (.not. c%spec%material%solid%is_elastic()) then
            block
                real(dp) :: omega, td, qlo, qhi
                call c%spec%material%solid%loss_peak(omega, td)
                qlo = c%grid%q0(); qhi = 0.5_dp*c%grid%nx*c%grid%q0()
                if (c%spec%surface%kind == 'self_affine') then
                    qlo = c%spec%surface%k_low*c%grid%q0(); qhi = c%spec%surface%k_cut*c%grid%q0()
                end if
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
        write (b, '(a,f8.3,a,f8.3,a,f8.3,a)') "  time: surface ", r%get('surface_seconds'), " s, kernel ", &
            r%get('kernel_seconds'), " s, solve ", r%get('solve_seconds'), " s"
        lines = [lines, b]
    contains
        function b_(t) result(l)
            character(len=*), intent(in) :: t
            character(len=summary_width) :: l
            l = t
        end function b_
    end function summary_lines

end module veslide_summary
